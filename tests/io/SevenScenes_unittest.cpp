// 7-Scenes' own layout (frame-NNNNNN.color.png / .depth.png / .pose.txt):
// listed in frame order at frame_rate, depth 65535 read as no reading, the
// depth camera's poses turned into the colour camera's ground truth through
// the description's extrinsics, bad pose files named in one line, the
// "7scenes" preset picked by `auto` and beaten by a camera.ini.
#include <gtest/gtest.h>
#include <mrpt/math/CMatrixFixed.h>
#include <roislam/io/CFrameSource.h>
#include <roislam/io/CTumFrameSource.h>
#include <roislam/io/CameraPresets.h>
#include <roislam/io/SevenScenes.h>
#include <roislam/io/TumTrajectory.h>

#include <Eigen/Dense>
#include <filesystem>
#include <fstream>

#include "TumFolderFixture.h"

namespace fs = std::filesystem;
using roislam::io::TSensorChoice;
using roislam::io::TSensorDescription;
using roislam::iotest::expectError;
using roislam::iotest::smallCamera;

namespace
{
constexpr int kW = 16, kH = 12;

void writeText(const fs::path& file, const std::string& text)
{
  std::ofstream(file) << text;
}

/** The 4x4 matrix of `pose` as 7-Scenes writes it (tab separated rows). */
std::string poseText(const mrpt::poses::CPose3D& pose)
{
  const auto H = pose.getHomogeneousMatrixVal<mrpt::math::CMatrixDouble44>();
  std::ostringstream ss;
  ss.precision(17);
  for (int r = 0; r < 4; ++r)
    ss << H(r, 0) << '\t' << H(r, 1) << '\t' << H(r, 2) << '\t' << H(r, 3) << "\t\n";
  return ss.str();
}

mrpt::poses::CPose3D depthPose(std::size_t n)
{
  return mrpt::poses::CPose3D(0.1 * n, -0.05 * n, 1.0 + 0.02 * n, 0.1 * n, -0.05, 0.02 * n);
}

/** A 7-Scenes folder of the given frame numbers; depth 65535 at pixel (0, 0)
 *  and 0 at (1, 0). */
std::string writeSevenScenes(const fs::path& dir, const std::vector<std::size_t>& numbers)
{
  fs::create_directories(dir);
  for (std::size_t n : numbers)
  {
    char stem[32];
    std::snprintf(stem, sizeof stem, "frame-%06zu", n);
    cv::imwrite(
        (dir / (std::string(stem) + ".color.png")).string(),
        roislam::iotest::colourImage(kW, kH, static_cast<int>(n)));
    cv::Mat depth(kH, kW, CV_16UC1, cv::Scalar(1500 + n));
    depth.at<uint16_t>(0, 0) = 0xFFFF;
    depth.at<uint16_t>(0, 1) = 0;
    cv::imwrite((dir / (std::string(stem) + ".depth.png")).string(), depth);
    writeText(dir / (std::string(stem) + ".pose.txt"), poseText(depthPose(n)));
  }
  return dir.string();
}

/** A registered millimetre camera of the small test images. */
TSensorChoice smallSensor(const mrpt::poses::CPose3D& depthInColour, bool registered)
{
  TSensorChoice c;
  c.sensor.name = "small";
  c.sensor.colour = smallCamera(kW, kH);
  c.sensor.depth = smallCamera(kW, kH);
  c.sensor.depth_registered = registered;
  c.sensor.depth_pose_in_colour = depthInColour;
  c.sensor.depth_scale = 1000;
  c.sensor.frame_rate = 20;
  c.source = "test";
  return c;
}
}  // namespace

TEST(SevenScenes, FramesInOrderAtTheFrameRateAndNoReadingAt65535)
{
  roislam::testing::CTempDir tmp("seven_scenes_frames");
  // Out of order on disk and not from 0; a stray file is ignored.
  // A sequence cut to start at frame 5 is one too.
  EXPECT_TRUE(
      roislam::io::isSevenScenesFolder(writeSevenScenes(fs::path(tmp.path()) / "cut", {5, 6})));
  EXPECT_FALSE(roislam::io::isSevenScenesFolder(tmp.path() + "/none"));
  const auto dir = writeSevenScenes(fs::path(tmp.path()) / "seq-01", {0, 2, 1, 10});
  writeText(fs::path(dir) / "notes.txt", "not a frame\n");
  EXPECT_TRUE(roislam::io::isSevenScenesFolder(dir));
  const auto frames = roislam::io::listSevenScenesFrames(dir);
  ASSERT_EQ(frames.size(), 4u);
  EXPECT_EQ(frames[1].number, 1u);
  EXPECT_EQ(frames[3].number, 10u);

  roislam::io::CTumFrameSource src(
      dir, smallSensor(mrpt::poses::CPose3D(), true), roislam::io::CTumFrameSource::TOptions());
  ASSERT_EQ(src.size(), 4u);
  std::vector<double> stamps;
  while (const auto f = src.next())
  {
    stamps.push_back(f->timestamp);
    EXPECT_EQ(f->depth.at<float>(0, 0), 0.0f) << "65535 is no reading";
    EXPECT_EQ(f->depth.at<float>(0, 1), 0.0f);
    EXPECT_FLOAT_EQ(f->depth.at<float>(5, 5), (1500.0f + f->timestamp * 20) / 1000);
  }
  EXPECT_EQ(stamps, (std::vector<double>{0, 0.05, 0.1, 0.5}));
  EXPECT_EQ(src.name(), "seq-01");
}

TEST(SevenScenes, GroundTruthIsTheColourCameraThroughTheExtrinsics)
{
  roislam::testing::CTempDir tmp("seven_scenes_gt");
  const auto dir = writeSevenScenes(fs::path(tmp.path()) / "seq-02", {0, 1, 2, 3});
  // Frame 2's pose is unknown (KinectFusion lost): left out, not an error.
  writeText(
      fs::path(dir) / "frame-000002.pose.txt",
      "-inf -inf -inf -inf\n-inf -inf -inf -inf\n-inf -inf -inf -inf\n0 0 0 1\n");
  const mrpt::poses::CPose3D depthInColour(-0.025, 0.003, 0.001, 0.05, -0.02, 0.01);
  std::string gtFile;
  {
    roislam::io::CTumFrameSource src(
        dir, smallSensor(depthInColour, false), roislam::io::CTumFrameSource::TOptions());
    ASSERT_TRUE(src.groundTruthFile());
    gtFile = *src.groundTruthFile();
    const auto gt = roislam::io::loadTumTrajectory(gtFile);
    ASSERT_EQ(gt.size(), 3u);
    const std::vector<std::size_t> numbers = {0, 1, 3};
    for (std::size_t k = 0; k < gt.size(); ++k)
    {
      EXPECT_DOUBLE_EQ(gt[k].timestamp, numbers[k] / 20.0);
      // World <- colour = world <- depth (+) depth <- colour.
      const mrpt::poses::CPose3D expected = depthPose(numbers[k]) + (-depthInColour);
      const mrpt::poses::CPose3D d = gt[k].pose - expected;
      EXPECT_LT(d.translation().norm(), 1e-9) << k;
      EXPECT_LT(
          (d.getRotationMatrix().asEigen() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(),
          1e-9)
          << k;
    }
    // The colour camera sits 2.5 cm from the depth camera: a real offset.
    EXPECT_GT((gt[0].pose.translation() - depthPose(0).translation()).norm(), 0.02);
  }
  EXPECT_FALSE(fs::exists(gtFile)) << "the source's ground truth outlives it";
  EXPECT_FALSE(fs::exists(fs::path(gtFile).parent_path()));

  // Registered depth: the poses are the colour camera's as they are.
  roislam::io::CTumFrameSource reg(
      dir, smallSensor(depthInColour, true), roislam::io::CTumFrameSource::TOptions());
  const auto gt = roislam::io::loadTumTrajectory(*reg.groundTruthFile());
  EXPECT_LT((gt[1].pose.translation() - depthPose(1).translation()).norm(), 1e-9);
}

TEST(SevenScenes, BadFoldersAndPoseFilesNameTheFile)
{
  roislam::testing::CTempDir tmp("seven_scenes_bad");
  const auto options = roislam::io::CTumFrameSource::TOptions();
  const auto sensor = smallSensor(mrpt::poses::CPose3D(), true);
  const fs::path root(tmp.path());

  const auto noDepth = writeSevenScenes(root / "nodepth", {0, 1});
  fs::remove(fs::path(noDepth) / "frame-000001.depth.png");
  expectError(
      [&] { roislam::io::CTumFrameSource(noDepth, sensor, options); },
      "frame-000001.color.png: no depth image beside it");

  const auto shortPose = writeSevenScenes(root / "shortpose", {0, 1});
  writeText(fs::path(shortPose) / "frame-000001.pose.txt", "1 0 0 0\n0 1 0 0\n0 0 1 0\n");
  expectError(
      [&] { roislam::io::CTumFrameSource(shortPose, sensor, options); },
      "frame-000001.pose.txt: expected a 4x4 matrix (16 numbers), got 12");

  const auto word = writeSevenScenes(root / "word", {0});
  writeText(fs::path(word) / "frame-000000.pose.txt", "1 0 0 0\n0 1 0 x\n0 0 1 0\n0 0 0 1\n");
  expectError(
      [&] { roislam::io::CTumFrameSource(word, sensor, options); },
      "frame-000000.pose.txt: not a number: 'x'");

  const auto sheared = writeSevenScenes(root / "sheared", {0});
  writeText(fs::path(sheared) / "frame-000000.pose.txt", "1 0.2 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n");
  expectError(
      [&] { roislam::io::CTumFrameSource(sheared, sensor, options); },
      "frame-000000.pose.txt: not a rigid transform");

  // A depth image of the wrong size is named when read.
  const auto big = writeSevenScenes(root / "big", {0});
  cv::imwrite(
      (fs::path(big) / "frame-000000.depth.png").string(),
      cv::Mat(kH * 2, kW * 2, CV_16UC1, cv::Scalar(1000)));
  roislam::io::CTumFrameSource src(big, sensor, options);
  expectError([&] { src.next(); }, "frame-000000.depth.png: image is 32x24");

  // rgb.txt makes it a TUM folder, whatever else it holds.
  const auto both = writeSevenScenes(root / "both", {0});
  writeText(fs::path(both) / "rgb.txt", "");
  EXPECT_FALSE(roislam::io::isSevenScenesFolder(both));
}

TEST(SevenScenes, AutoPicksThePresetUnlessTheFolderDescribesItsCamera)
{
  roislam::testing::CTempDir tmp("seven_scenes_auto");
  const auto dir = writeSevenScenes(fs::path(tmp.path()) / "seq-03", {0, 1});
  const auto choice = roislam::io::resolveSensor("auto", dir);
  EXPECT_EQ(choice.source, "preset 7scenes");
  EXPECT_NE(choice.reason.find("7-Scenes frames"), std::string::npos) << choice.reason;
  const TSensorDescription& p = choice.sensor;
  EXPECT_FALSE(p.depth_registered);
  EXPECT_DOUBLE_EQ(p.depth.fx(), 585);
  EXPECT_DOUBLE_EQ(p.depth.cx(), 320);
  EXPECT_DOUBLE_EQ(p.depth_scale, 1000);
  EXPECT_DOUBLE_EQ(p.depth_pose_in_colour.x(), -0.025);
  EXPECT_EQ(roislam::io::resolveSensor("7scenes", ".").source, "preset 7scenes");

  // A camera.ini in the folder wins (here: the small images' camera).
  roislam::iotest::writeCameraIni((fs::path(dir) / "camera.ini").string(), smallCamera(kW, kH));
  const auto own = roislam::io::CFrameSource::open(dir, "auto");
  EXPECT_EQ(own->sensor().reason, "camera.ini in the folder");
  EXPECT_EQ(own->size(), 2u);
  ASSERT_TRUE(own->next());
}
