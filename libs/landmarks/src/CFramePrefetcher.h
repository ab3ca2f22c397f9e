/* Private: reads frames on a second thread (PNG decoding costs about as much
 * as the ORB pipeline), a few frames ahead of the consumer. Used by
 * CRoiLandmarksApp.
 */
#pragma once

#include <roislam/io/CFrameSource.h>

#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>

namespace roislam::landmarks::detail
{
class CFramePrefetcher
{
 public:
  /** Starts reading at most maxFrames frames (0 = all) from source. */
  CFramePrefetcher(io::CFrameSource& source, std::size_t maxFrames);
  ~CFramePrefetcher();
  CFramePrefetcher(const CFramePrefetcher&) = delete;
  CFramePrefetcher& operator=(const CFramePrefetcher&) = delete;

  /** The next frame, nullopt at the end; rethrows the reader's exception. */
  std::optional<io::TRGBDFrame> next();

 private:
  void run(io::CFrameSource& source, std::size_t maxFrames);

  static constexpr std::size_t kDepth = 4;
  std::mutex m_mutex;
  std::condition_variable m_cv;
  std::deque<io::TRGBDFrame> m_queue;
  bool m_done = false;
  bool m_stop = false;
  std::exception_ptr m_error;
  std::thread m_thread;  // last: starts after the other members exist
};
}  // namespace roislam::landmarks::detail
