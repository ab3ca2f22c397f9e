/* CPingPongFrameSource: a sequence played there and back, for soak tests:
 * the bounce order, increasing stamps with the original spacing, the same
 * images as the source's frames, and seek() on both source kinds. */
#include <gtest/gtest.h>
#include <roislam/io/CPingPongFrameSource.h>
#include <roislam/io/CRawlogFrameSource.h>
#include <roislam/io/CTum2RawlogApp.h>
#include <roislam/io/CTumFrameSource.h>

#include <filesystem>
#include <vector>

#include "TumFolderFixture.h"

namespace fs = std::filesystem;
using namespace roislam::io;
using namespace roislam::iotest;

TEST(PingPongFrameSource, PlaysThereAndBackWithIncreasingStamps)
{
  const auto tmp = roislam::testing::makeTempDir("io_pingpong");
  const std::vector<double> stamps{1.0, 1.1, 1.3, 1.6};
  const auto dir = writeTumFolder(tmp, "seq", stamps, {1.0, 1.1, 1.3, 1.6});
  CPingPongFrameSource p(std::make_unique<CTumFrameSource>(dir, smallCamera()), 11);
  EXPECT_EQ(p.size(), 11u);
  EXPECT_FALSE(p.groundTruthFile());
  const std::vector<std::size_t> order{0, 1, 2, 3, 2, 1, 0, 1, 2, 3, 2};
  std::vector<double> expectedStamps{1.0};
  for (std::size_t k = 1; k < order.size(); ++k)
    expectedStamps.push_back(
        expectedStamps.back() + std::abs(stamps[order[k]] - stamps[order[k - 1]]));
  CTumFrameSource plain(dir, smallCamera());
  std::vector<cv::Mat> images;
  while (auto f = plain.next())
    images.push_back(f->rgb);
  for (std::size_t k = 0; k < order.size(); ++k)
  {
    EXPECT_EQ(p.sourceIndex(k), order[k]);
    const auto f = p.next();
    ASSERT_TRUE(f) << k;
    EXPECT_EQ(f->index, k);
    EXPECT_NEAR(f->timestamp, expectedStamps[k], 1e-9) << k;
    EXPECT_NEAR(f->depthTimestamp, f->timestamp, 1e-9);
    EXPECT_EQ(cv::norm(f->rgb, images[order[k]], cv::NORM_INF), 0.0) << k;
  }
  EXPECT_FALSE(p.next());
  // The played folder timed its frames (none on a clock: 100-300 ms apart).
  ASSERT_TRUE(p.frameClock());
  EXPECT_EQ(p.frameClock()->frames, 4u);
  EXPECT_EQ(p.frameClock()->clocked, 0u);
  p.rewind();
  ASSERT_TRUE(p.next());

  // A rawlog source seeks without loading images; same frames.
  CTum2RawlogApp::TOptions o;
  o.input = dir;
  o.output = tmp + "/seq.rawlog";
  o.camera = "auto";
  writeCameraIni(dir + "/camera.ini", smallCamera());
  CTum2RawlogApp(o).run();
  CPingPongFrameSource r(std::make_unique<CRawlogFrameSource>(o.output), 8);
  for (std::size_t k = 0; k < 8; ++k)
  {
    const auto f = r.next();
    ASSERT_TRUE(f);
    EXPECT_EQ(cv::norm(f->rgb, images[order[k]], cv::NORM_INF), 0.0) << k;
  }
  EXPECT_THROW(CPingPongFrameSource(nullptr, 5), std::invalid_argument);
  fs::remove_all(tmp);
}

TEST(PingPongFrameSource, DepthOffsetIsMirroredBackwards)
{
  // Depth 10 ms after colour: after it going forwards, before it backwards.
  const auto tmp = roislam::testing::makeTempDir("io_pingpong_depth");
  const auto dir = writeTumFolder(tmp, "seq", {1.0, 1.1, 1.3, 1.6}, {1.01, 1.11, 1.31, 1.61});
  CPingPongFrameSource p(std::make_unique<CTumFrameSource>(dir, smallCamera()), 11);
  // Frames 0 1 2 3 2 1 0 1 2 3 2: a frame reached by a step back is backwards.
  const std::vector<double> sign{1, 1, 1, 1, -1, -1, -1, 1, 1, 1, -1};
  for (std::size_t k = 0; k < sign.size(); ++k)
  {
    const auto f = p.next();
    ASSERT_TRUE(f) << k;
    EXPECT_NEAR(f->depthTimestamp - f->timestamp, sign[k] * 0.01, 1e-9) << k;
  }
  fs::remove_all(tmp);
}
