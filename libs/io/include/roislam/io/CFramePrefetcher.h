/* Decodes the frames of a source on a second thread, ahead of their consumer:
 * while frame i is processed, frame i+1 (or up to `depth` frames) is read
 * (PNG decoding costs about as much as the ORB pipeline) and, optionally,
 * prepared by a function run on that thread too (e.g. stage 1, the ROI,
 * detected one frame ahead). The one prefetcher of the project: used by
 * roi-landmarks (CRoiLandmarksApp) and meant for roi-graphslam's
 * CSlamPipeline.
 *
 *   io::CFramePrefetcher<std::optional<THint>> ahead(
 *       source, 1, [&](const io::TRGBDFrame& f) { return detectAhead(f); });
 *   while (auto item = ahead.next())
 *     process(item->frame, item->prepared);
 *
 * The source and whatever `prepare` uses must outlive the prefetcher and must
 * not be used by the consumer meanwhile (the source is read on the second
 * thread). Not thread-safe itself: one consumer.
 */
#pragma once

#include <roislam/io/CFrameSource.h>

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>
#include <utility>
#include <variant>

namespace roislam::io
{
template <typename TPrepared = std::monostate>
class CFramePrefetcher
{
 public:
  struct TItem
  {
    TRGBDFrame frame;
    /** prepare(frame), or a default TPrepared without a prepare function. */
    TPrepared prepared{};
  };
  using TPrepare = std::function<TPrepared(const TRGBDFrame&)>;

  /** Starts reading at once. depth >= 1: decoded frames waiting at most (1 =
   *  frame i+1 while i is processed); maxFrames: frames read at most, 0 =
   *  all. Throws std::invalid_argument on depth 0. */
  explicit CFramePrefetcher(
      CFrameSource& source, std::size_t depth = 1, TPrepare prepare = {}, std::size_t maxFrames = 0)
      : m_depth(depth)
  {
    if (depth == 0)
      throw std::invalid_argument("CFramePrefetcher: depth must be >= 1");
    m_thread = std::thread([this, &source, prepare = std::move(prepare), maxFrames]
                           { run(source, prepare, maxFrames); });
  }
  /** Stops reading (a decode under way finishes first). */
  ~CFramePrefetcher()
  {
    {
      std::lock_guard<std::mutex> lock(m_mutex);
      m_stop = true;
    }
    m_cv.notify_all();
    m_thread.join();
  }
  CFramePrefetcher(const CFramePrefetcher&) = delete;
  CFramePrefetcher& operator=(const CFramePrefetcher&) = delete;

  /** The next frame in order, nullopt at the end; once the frames read
   *  before an error are taken, rethrows the exception of the source or of
   *  prepare. */
  std::optional<TItem> next()
  {
    std::unique_lock<std::mutex> lock(m_mutex);
    m_cv.wait(lock, [&] { return !m_queue.empty() || m_done; });
    if (m_queue.empty())
    {
      if (m_error)
        std::rethrow_exception(m_error);
      return std::nullopt;
    }
    TItem item = std::move(m_queue.front());
    m_queue.pop_front();
    m_cv.notify_all();
    return item;
  }

  /** Blocks until next() would not: the time a consumer would wait for the
   *  next frame (benchmarks that time several consumers in turn). */
  void waitReady() const
  {
    std::unique_lock<std::mutex> lock(m_mutex);
    m_cv.wait(lock, [&] { return !m_queue.empty() || m_done; });
  }

 private:
  void run(CFrameSource& source, const TPrepare& prepare, std::size_t maxFrames)
  {
    try
    {
      for (std::size_t n = 0; maxFrames == 0 || n < maxFrames; ++n)
      {
        {
          std::unique_lock<std::mutex> lock(m_mutex);
          m_cv.wait(lock, [&] { return m_queue.size() < m_depth || m_stop; });
          if (m_stop)
            break;
        }
        std::optional<TRGBDFrame> f = source.next();
        if (!f)
          break;
        TItem item{std::move(*f), {}};
        if (prepare)
          item.prepared = prepare(item.frame);
        std::lock_guard<std::mutex> lock(m_mutex);
        m_queue.push_back(std::move(item));
        m_cv.notify_all();
      }
    }
    catch (...)
    {
      std::lock_guard<std::mutex> lock(m_mutex);
      m_error = std::current_exception();
    }
    std::lock_guard<std::mutex> lock(m_mutex);
    m_done = true;
    m_cv.notify_all();
  }

  const std::size_t m_depth;
  mutable std::mutex m_mutex;
  mutable std::condition_variable m_cv;
  std::deque<TItem> m_queue;
  bool m_done = false;
  bool m_stop = false;
  std::exception_ptr m_error;
  std::thread m_thread;  // started last, in the constructor's body
};
}  // namespace roislam::io
