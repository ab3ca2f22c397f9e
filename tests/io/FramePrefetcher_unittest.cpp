// CFramePrefetcher: frames in order, the preparation run on the second thread,
// at most `depth` frames read ahead, maxFrames, errors delivered after the
// frames read before them, and a clean stop with frames left unread.
#include <gtest/gtest.h>
#include <roislam/io/CFramePrefetcher.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>

using roislam::io::CFramePrefetcher;
using roislam::io::TRGBDFrame;

namespace
{
/** Frames 0..n-1; throws when asked for frame `failAt`. */
class CCountingSource : public roislam::io::CFrameSource
{
 public:
  explicit CCountingSource(std::size_t n, std::size_t failAt = SIZE_MAX) : m_n(n), m_failAt(failAt)
  {
  }
  std::optional<TRGBDFrame> next() override
  {
    const std::size_t i = m_reads++;
    if (i == m_failAt)
      throw std::runtime_error("frame " + std::to_string(i) + ": corrupt");
    if (i >= m_n)
      return std::nullopt;
    TRGBDFrame f;
    f.index = i;
    f.timestamp = 0.5 * static_cast<double>(i);
    return f;
  }
  void rewind() override { m_reads = 0; }
  std::size_t size() const override { return m_n; }
  const mrpt::img::TCamera& camera() const override { return m_camera; }
  std::optional<std::string> groundTruthFile() const override { return std::nullopt; }
  std::string name() const override { return "counting"; }
  std::size_t reads() const { return m_reads; }

 private:
  std::size_t m_n, m_failAt;
  std::atomic<std::size_t> m_reads{0};
  mrpt::img::TCamera m_camera;
};

void waitFor(const std::function<bool()>& done)
{
  for (int i = 0; i < 2000 && !done(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
}
}  // namespace

TEST(FramePrefetcher, FramesInOrderPreparedOnTheSecondThread)
{
  CCountingSource source(5);
  const auto consumer = std::this_thread::get_id();
  CFramePrefetcher<std::pair<double, bool>> ahead(
      source, 1,
      [&](const TRGBDFrame& f)
      { return std::make_pair(2 * f.timestamp, std::this_thread::get_id() != consumer); });
  for (std::size_t i = 0; i < 5; ++i)
  {
    auto item = ahead.next();
    ASSERT_TRUE(item);
    EXPECT_EQ(item->frame.index, i);
    EXPECT_DOUBLE_EQ(item->prepared.first, static_cast<double>(i));
    EXPECT_TRUE(item->prepared.second);
  }
  EXPECT_FALSE(ahead.next());
  EXPECT_FALSE(ahead.next());
}

TEST(FramePrefetcher, ReadsAtMostDepthFramesAhead)
{
  for (std::size_t depth : {1u, 3u})
  {
    CCountingSource source(10);
    CFramePrefetcher<> ahead(source, depth);
    ahead.waitReady();
    waitFor([&] { return source.reads() >= depth; });
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
    EXPECT_EQ(source.reads(), depth);
    ASSERT_TRUE(ahead.next());  // room for one more
    waitFor([&] { return source.reads() >= depth + 1; });
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
    EXPECT_EQ(source.reads(), depth + 1);
  }
  CCountingSource source(1);
  EXPECT_THROW(CFramePrefetcher<>(source, 0), std::invalid_argument);
}

TEST(FramePrefetcher, MaxFrames)
{
  CCountingSource source(10);
  CFramePrefetcher<> ahead(source, 4, {}, 3);
  int n = 0;
  while (ahead.next())
    ++n;
  EXPECT_EQ(n, 3);
  EXPECT_EQ(source.reads(), 3u);
}

TEST(FramePrefetcher, ErrorsComeAfterTheFramesBeforeThem)
{
  CCountingSource source(10, 2);
  CFramePrefetcher<> ahead(source, 4);
  EXPECT_EQ(ahead.next()->frame.index, 0u);
  EXPECT_EQ(ahead.next()->frame.index, 1u);
  EXPECT_THROW(ahead.next(), std::runtime_error);

  CCountingSource ok(10);
  CFramePrefetcher<int> failing(
      ok, 1,
      [](const TRGBDFrame& f)
      {
        if (f.index == 1)
          throw std::invalid_argument("no ROI");
        return 7;
      });
  EXPECT_EQ(failing.next()->prepared, 7);
  EXPECT_THROW(failing.next(), std::invalid_argument);
}

TEST(FramePrefetcher, StopsWithFramesLeft)
{
  CCountingSource source(1000);
  {
    CFramePrefetcher<> ahead(source, 2);
    ASSERT_TRUE(ahead.next());
  }  // must not hang
  EXPECT_LE(source.reads(), 4u);
}
