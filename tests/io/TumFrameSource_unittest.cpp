/* CTumFrameSource and CFrameSource::open on TUM folders: the shared fr1/rpy
 * sequence, association semantics on constructed stamp lists, bad input. */
#include <mrpt/config/CConfigFileMemory.h>
#include <roislam/io/CFrameSource.h>
#include <roislam/io/CTumFrameSource.h>
#include <roislam/io/CameraPresets.h>
#include <roislam/testing/TestData.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "TumFolderFixture.h"

namespace fs = std::filesystem;
using roislam::io::CFrameSource;
using roislam::io::CTumFrameSource;
using namespace roislam::iotest;

TEST(TumFrameSource, SharedSequenceAssociationAndFrames)
{
  ROISLAM_REQUIRE_SHARED_TUM(dir);
  auto src = CFrameSource::open(dir);
  ASSERT_TRUE(src);
  // All 250 colour frames find a depth partner within 0.02 s (checked against
  // associate.py semantics by hand: largest |dt| is 0.0141 s).
  EXPECT_EQ(src->size(), 250u);
  EXPECT_EQ(src->skippedFrames(), 0u);
  EXPECT_EQ(src->name(), "rgbd_dataset_freiburg1_rpy_first250");
  ASSERT_TRUE(src->groundTruthFile());
  EXPECT_EQ(
      *src->groundTruthFile(), (fs::path(dir) / "groundtruth.txt").lexically_normal().string());

  // auto -> Freiburg 1 from the folder name.
  EXPECT_DOUBLE_EQ(src->camera().fx(), 517.306408);
  EXPECT_DOUBLE_EQ(src->camera().fy(), 516.469215);
  EXPECT_DOUBLE_EQ(src->camera().cx(), 318.643040);
  EXPECT_DOUBLE_EQ(src->camera().cy(), 255.313989);

  auto first = src->next();
  ASSERT_TRUE(first);
  EXPECT_EQ(first->index, 0u);
  // The colour image's time: the first frame's stamp (the camera's clock
  // starts there) plus the fr1 description's colour_time_offset_ms (-7); the
  // depth image keeps its stamp.
  EXPECT_NEAR(first->timestamp, 1305031229.528748 - 0.007, 1e-9);
  EXPECT_DOUBLE_EQ(first->depthTimestamp, 1305031229.528784);
  EXPECT_EQ(first->rgb.type(), CV_8UC3);
  EXPECT_EQ(first->depth.type(), CV_32FC1);
  EXPECT_EQ(first->rgb.size(), cv::Size(640, 480));
  EXPECT_EQ(first->depth.size(), cv::Size(640, 480));
  EXPECT_EQ(first->grey().type(), CV_8UC1);

  // Depth equals raw / 5000 exactly, 0 stays 0, values plausible for a desk.
  const cv::Mat raw =
      cv::imread((fs::path(dir) / "depth/1305031229.528784.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(raw.type(), CV_16UC1);
  std::size_t valid = 0;
  std::vector<float> values;
  for (int r = 0; r < raw.rows; ++r)
    for (int c = 0; c < raw.cols; ++c)
    {
      const float d = first->depth.at<float>(r, c);
      ASSERT_EQ(d, static_cast<float>(raw.at<uint16_t>(r, c) / 5000.0));
      if (d > 0)
      {
        ++valid;
        values.push_back(d);
      }
    }
  EXPECT_GT(valid, raw.total() / 2);
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  const float median = values[values.size() / 2];
  EXPECT_GT(median, 0.5f);
  EXPECT_LT(median, 4.0f);

  // Associations of the whole sequence (images of every frame are decoded by
  // the tum2rawlog integration test): increasing stamps, |dt| < 0.02 s.
  const auto* tum = dynamic_cast<const CTumFrameSource*>(src.get());
  ASSERT_NE(tum, nullptr);
  const auto& entries = tum->entries();
  ASSERT_EQ(entries.size(), 250u);
  for (std::size_t k = 1; k < entries.size(); ++k)
  {
    EXPECT_GT(entries[k].rgbStamp, entries[k - 1].rgbStamp);
    EXPECT_GT(entries[k].depthStamp, entries[k - 1].depthStamp);
    EXPECT_LT(std::abs(entries[k].rgbStamp - entries[k].depthStamp), 0.02);
  }
  EXPECT_DOUBLE_EQ(entries.back().rgbStamp, 1305031237.829769);
  EXPECT_DOUBLE_EQ(entries.back().depthStamp, 1305031237.843031);
  auto second = src->next();
  ASSERT_TRUE(second);
  EXPECT_EQ(second->index, 1u);
  EXPECT_EQ(second->timestamp, entries[1].time);

  // The frames' times lie on a clock, 7 ms before it: fr1's stamps jitter by
  // 1.9 ms RMS around one (up to 3.8 ms), the times by far less.
  const auto clock = src->frameClock();
  ASSERT_TRUE(clock);
  EXPECT_EQ(clock->frames, 250u);
  EXPECT_EQ(clock->clocked, 246u);  // from the fifth frame
  EXPECT_EQ(clock->restarts, 0u);
  EXPECT_GT(clock->rmsCorrectionMs, 1.0);
  EXPECT_LT(clock->maxCorrectionMs, 8.0);
  double stampJitter = 0, timeJitter = 0;
  for (std::size_t k = 2; k < entries.size(); ++k)
  {
    EXPECT_NEAR(entries[k].time, entries[k].rgbStamp - 0.007, 0.008) << k;
    const auto second = [&](auto get)
    { return get(entries[k]) - 2 * get(entries[k - 1]) + get(entries[k - 2]); };
    stampJitter += std::pow(second([](const auto& e) { return e.rgbStamp; }), 2);
    timeJitter += std::pow(second([](const auto& e) { return e.time; }), 2);
  }
  EXPECT_LT(timeJitter, stampJitter / 25) << "second differences: the times are regular";

  src->rewind();
  auto again = src->next();
  ASSERT_TRUE(again);
  EXPECT_EQ(again->index, 0u);
  EXPECT_EQ(cv::norm(again->rgb, first->rgb, cv::NORM_INF), 0.0);
}

TEST(TumFrameSource, AssociationIsGreedyOneToOneWithinWindow)
{
  const auto tmp = roislam::testing::makeTempDir("io_tum_assoc");
  // rgb 1.000 and 1.010 compete for depth 1.008 (the closer, 1.010, wins);
  // rgb 1.000 then takes depth 0.985 (|dt| 0.015 < 0.02). rgb 2.000 has only
  // depth 2.020 (|dt| = 0.020, not < 0.02) -> skipped. rgb 3.000 / depth 3.019 pair.
  const auto dir =
      writeTumFolder(tmp, "seq", {1.000, 1.010, 2.000, 3.000}, {0.985, 1.008, 2.020, 3.019});
  CTumFrameSource src(dir, smallCamera());
  ASSERT_EQ(src.size(), 3u);
  EXPECT_EQ(src.skippedFrames(), 1u);
  const auto& e = src.entries();
  EXPECT_DOUBLE_EQ(e[0].rgbStamp, 1.000);
  EXPECT_DOUBLE_EQ(e[0].depthStamp, 0.985);
  EXPECT_DOUBLE_EQ(e[1].rgbStamp, 1.010);
  EXPECT_DOUBLE_EQ(e[1].depthStamp, 1.008);
  EXPECT_DOUBLE_EQ(e[2].rgbStamp, 3.000);
  EXPECT_DOUBLE_EQ(e[2].depthStamp, 3.019);
  EXPECT_FALSE(src.groundTruthFile());
  EXPECT_FALSE(src.accelerometerFile());

  // next() stamps each frame with its entry's stamps, so entries() gives a
  // sequence's frame stamps without decoding (as the soak test reads them).
  for (std::size_t k = 0; k < e.size(); ++k)
  {
    const auto frame = src.next();
    ASSERT_TRUE(frame);
    EXPECT_EQ(frame->index, k);
    EXPECT_EQ(frame->timestamp, e[k].rgbStamp);
    EXPECT_EQ(frame->depthTimestamp, e[k].depthStamp);
  }
  EXPECT_FALSE(src.next());
  src.rewind();

  // Frames carry the images of the associated files (depth image index 1 for
  // the second frame) and metres = raw / 5000.
  src.next();
  auto f = src.next();
  ASSERT_TRUE(f);
  EXPECT_EQ(cv::norm(f->rgb, colourImage(16, 12, 1), cv::NORM_INF), 0.0);
  const cv::Mat raw = depthImage(16, 12, 1);
  for (int r = 0; r < raw.rows; ++r)
    for (int c = 0; c < raw.cols; ++c)
      EXPECT_EQ(f->depth.at<float>(r, c), static_cast<float>(raw.at<uint16_t>(r, c) / 5000.0));
  fs::remove_all(tmp);
}

TEST(TumFrameSource, OptionsWindowAndScale)
{
  const auto tmp = roislam::testing::makeTempDir("io_tum_opts");
  const auto dir = writeTumFolder(tmp, "seq", {1.0, 2.0}, {1.03, 2.0});
  CTumFrameSource::TOptions opts;
  opts.maxTimeDifference = 0.05;
  opts.depthScale = 1000;
  CTumFrameSource src(dir, smallCamera(), opts);
  EXPECT_EQ(src.size(), 2u);
  EXPECT_EQ(src.skippedFrames(), 0u);
  auto f = src.next();
  ASSERT_TRUE(f);
  EXPECT_EQ(
      f->depth.at<float>(0, 1),
      static_cast<float>(depthImage(16, 12, 0).at<uint16_t>(0, 1) / 1000.0));

  mrpt::config::CConfigFileMemory cfg;
  cfg.write("TumFrameSource", "max_time_difference", -1.0);
  CTumFrameSource::TOptions bad;
  expectError([&] { bad.loadFromConfigFile(cfg, "TumFrameSource"); }, "max_time_difference");
  fs::remove_all(tmp);
}

TEST(TumFrameSource, CameraFromCameraIniWinsForAuto)
{
  const auto tmp = roislam::testing::makeTempDir("io_tum_cam");
  const auto dir = writeTumFolder(tmp, "rgbd_dataset_freiburg1_sim", {1.0}, {1.0});
  writeCameraIni((fs::path(dir) / "camera.ini").string(), smallCamera());
  auto src = CFrameSource::open(dir);
  EXPECT_DOUBLE_EQ(src->camera().fx(), 20.0);
  EXPECT_EQ(src->camera().ncols, 16u);
  auto f = src->next();
  ASSERT_TRUE(f);
  EXPECT_DOUBLE_EQ(f->camera.fy(), 21.0);
  // An explicit preset overrides camera.ini; here it then fails the size check.
  auto fr1 = CFrameSource::open(dir, "fr1");
  expectError([&] { fr1->next(); }, "16x12");
  fs::remove_all(tmp);
}

TEST(TumFrameSource, BadInput)
{
  const auto tmp = roislam::testing::makeTempDir("io_tum_bad");
  const auto cam = smallCamera();
  expectError([&] { CFrameSource::open(tmp + "/nope"); }, tmp + "/nope");
  expectError([&] { CTumFrameSource(tmp + "/nope", cam); }, "nope");

  // Missing rgb.txt / depth.txt.
  auto dir = writeTumFolder(tmp, "norgb", {1.0}, {1.0});
  fs::remove(fs::path(dir) / "rgb.txt");
  expectError([&] { CTumFrameSource(dir, cam); }, "rgb.txt");
  dir = writeTumFolder(tmp, "nodepth", {1.0}, {1.0});
  fs::remove(fs::path(dir) / "depth.txt");
  expectError([&] { CTumFrameSource(dir, cam); }, "depth.txt");

  // Malformed lines name file and line (comments count as lines).
  dir = writeTumFolder(tmp, "malformed", {1.0, 2.0}, {1.0, 2.0});
  {
    std::ofstream(fs::path(dir) / "rgb.txt", std::ios::app) << "abc rgb/x.png\n";
  }
  expectError([&] { CTumFrameSource(dir, cam); }, "rgb.txt:5:");
  {
    std::ofstream(fs::path(dir) / "rgb.txt") << "# c\n1.0\n";
  }
  expectError([&] { CTumFrameSource(dir, cam); }, "rgb.txt:2:");
  {
    std::ofstream(fs::path(dir) / "rgb.txt") << "1.0 rgb/1.000000.png\n";
    std::ofstream(fs::path(dir) / "depth.txt") << "1.0 depth/1.000000.png extra\n";
  }
  expectError([&] { CTumFrameSource(dir, cam); }, "depth.txt:1:");

  // Nothing listed, or nothing associated.
  dir = writeTumFolder(tmp, "emptylist", {}, {1.0});
  expectError([&] { CTumFrameSource(dir, cam); }, "rgb.txt: no frames listed");
  dir = writeTumFolder(tmp, "noassoc", {1.0, 2.0}, {1.5, 2.5});
  expectError([&] { CTumFrameSource(dir, cam); }, "no colour frame has a depth image");

  // Listed image missing: named at open.
  dir = writeTumFolder(tmp, "missing", {1.0, 2.0}, {1.0, 2.0});
  fs::remove(fs::path(dir) / "rgb/2.000000.png");
  expectError([&] { CTumFrameSource(dir, cam); }, "rgb/2.000000.png");

  // Corrupt colour image: named when read.
  dir = writeTumFolder(tmp, "corrupt", {1.0, 2.0}, {1.0, 2.0});
  {
    std::ofstream(fs::path(dir) / "rgb/2.000000.png", std::ios::trunc) << "not a png";
  }
  {
    CTumFrameSource src(dir, cam);
    ASSERT_TRUE(src.next());
    expectError([&] { src.next(); }, "rgb/2.000000.png");
  }

  // Depth not 16-bit.
  dir = writeTumFolder(tmp, "depth8", {1.0}, {1.0});
  cv::imwrite(
      (fs::path(dir) / "depth/1.000000.png").string(), cv::Mat(12, 16, CV_8UC1, cv::Scalar(7)));
  {
    CTumFrameSource src(dir, cam);
    expectError([&] { src.next(); }, "16-bit");
  }

  // Wrong sizes: colour, then depth, against the intrinsics (16x12).
  dir = writeTumFolder(tmp, "size", {1.0}, {1.0});
  cv::imwrite((fs::path(dir) / "rgb/1.000000.png").string(), colourImage(8, 12, 0));
  {
    CTumFrameSource src(dir, cam);
    expectError([&] { src.next(); }, "rgb/1.000000.png: image is 8x12");
  }
  dir = writeTumFolder(tmp, "dsize", {1.0}, {1.0});
  cv::imwrite((fs::path(dir) / "depth/1.000000.png").string(), depthImage(16, 10, 0));
  {
    CTumFrameSource src(dir, cam);
    expectError([&] { src.next(); }, "depth/1.000000.png: image is 16x10");
  }
  fs::remove_all(tmp);
}
