#include "CFramePrefetcher.h"

namespace roislam::landmarks::detail
{
CFramePrefetcher::CFramePrefetcher(io::CFrameSource& source, std::size_t maxFrames)
    : m_thread([this, &source, maxFrames] { run(source, maxFrames); })
{
}

CFramePrefetcher::~CFramePrefetcher()
{
  {
    std::lock_guard<std::mutex> lock(m_mutex);
    m_stop = true;
  }
  m_cv.notify_all();
  m_thread.join();
}

std::optional<io::TRGBDFrame> CFramePrefetcher::next()
{
  std::unique_lock<std::mutex> lock(m_mutex);
  m_cv.wait(lock, [&] { return !m_queue.empty() || m_done; });
  if (m_queue.empty())
  {
    if (m_error)
      std::rethrow_exception(m_error);
    return std::nullopt;
  }
  io::TRGBDFrame f = std::move(m_queue.front());
  m_queue.pop_front();
  m_cv.notify_all();
  return f;
}

void CFramePrefetcher::run(io::CFrameSource& source, std::size_t maxFrames)
{
  try
  {
    for (std::size_t n = 0; maxFrames == 0 || n < maxFrames; ++n)
    {
      auto f = source.next();
      std::unique_lock<std::mutex> lock(m_mutex);
      if (!f || m_stop)
        break;
      m_queue.push_back(std::move(*f));
      m_cv.notify_all();
      m_cv.wait(lock, [&] { return m_queue.size() < kDepth || m_stop; });
      if (m_stop)
        break;
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
}  // namespace roislam::landmarks::detail
