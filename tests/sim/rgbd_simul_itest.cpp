// The sequences written by the rgbd-simul app for the synthetic_data fixture,
// read back through roislam::io like every other app does, and the app's
// error handling.
#include <gtest/gtest.h>
#include <mrpt/core/bits_math.h>
#include <roislam/io/CFrameSource.h>
#include <roislam/io/TumTrajectory.h>
#include <roislam/sim/CSceneModel.h>
#include <roislam/testing/TestData.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace fs = std::filesystem;

namespace
{
/** Median distance of unprojected depth pixels to the scene surfaces. */
double medianSurfaceError(const roislam::io::TRGBDFrame& f, const mrpt::poses::CPose3D& pose)
{
  static const auto scene =
      roislam::sim::CSceneModel::build(roislam::sim::CSceneModel::TSceneType::Featureless);
  std::vector<double> err;
  for (int v = 0; v < f.depth.rows; v += 9)
    for (int u = 0; u < f.depth.cols; u += 9)
    {
      const float z = f.depth.at<float>(v, u);
      if (z <= 0)
        continue;
      const mrpt::math::TPoint3D pc(
          (u - f.camera.cx()) * z / f.camera.fx(), (v - f.camera.cy()) * z / f.camera.fy(), z);
      err.push_back(scene.distanceToSurface(pose.composePoint(pc)));
    }
  if (err.empty())
    return 1e9;
  std::nth_element(err.begin(), err.begin() + err.size() / 2, err.end());
  return err[err.size() / 2];
}

void checkSequence(const std::string& dir, std::size_t frames, int minOrb)
{
  auto src = roislam::io::CFrameSource::open(dir);
  ASSERT_EQ(src->size(), frames);
  EXPECT_DOUBLE_EQ(src->camera().fx(), 517.3);  // from camera.ini, not a preset
  EXPECT_DOUBLE_EQ(src->camera().cx(), 318.6);
  ASSERT_TRUE(src->groundTruthFile().has_value());
  const auto gt = roislam::io::loadTumTrajectory(*src->groundTruthFile());
  ASSERT_EQ(gt.size(), frames);

  // A loop: the last pose revisits the first.
  const auto d = gt.front().pose - gt.back().pose;
  EXPECT_LT(d.translation().norm(), 0.03);
  const auto R = d.getRotationMatrix();
  EXPECT_LT(
      mrpt::RAD2DEG(std::acos(std::clamp((R(0, 0) + R(1, 1) + R(2, 2) - 1) / 2, -1.0, 1.0))), 2.0);

  std::size_t i = 0;
  while (auto f = src->next())
  {
    ASSERT_LT(i, gt.size());
    EXPECT_NEAR(f->timestamp, gt[i].timestamp, 1e-6);
    EXPECT_LT(std::abs(f->depthTimestamp - f->timestamp), 0.02);
    if (i % 15 == 0)
    {
      // Noisy depth still lies on the known geometry (sigma is 2-9 mm here).
      EXPECT_LT(medianSurfaceError(*f, gt[i].pose), 0.006) << "frame " << i;
      std::vector<cv::KeyPoint> kps;
      cv::ORB::create(1000)->detect(f->grey(), kps);
      if (minOrb > 0)
        EXPECT_GE(static_cast<int>(kps.size()), minOrb) << "frame " << i;
      else
        EXPECT_LT(static_cast<int>(kps.size()), 400) << "frame " << i;
    }
    ++i;
  }
  EXPECT_EQ(i, frames);
}
}  // namespace

TEST(RgbdSimulApp, TexturedFixtureSequence)
{
  ROISLAM_REQUIRE_SYNTHETIC(dir, "textured");
  checkSequence(dir, 90, 800);
}

TEST(RgbdSimulApp, FeaturelessFixtureSequence)
{
  ROISLAM_REQUIRE_SYNTHETIC(dir, "featureless");
  checkSequence(dir, 60, 0);
}

TEST(RgbdSimulApp, UnwritableOutputIsAOneLineError)
{
  const std::string exe = roislam::testing::binaryDir() + "/apps/rgbd-simul/rgbd-simul";
  if (!fs::exists(exe))
    GTEST_SKIP() << exe << " not built";
  const std::string dir = roislam::testing::makeTempDir("simul_app");
  const fs::path file = fs::path(dir) / "file.txt";
  std::ofstream(file) << "x";
  const fs::path err = fs::path(dir) / "stderr.txt";
  const std::string cmd = "'" + exe + "' --output '" + (file / "out").string() +
                          "' --frames 2 2>'" + err.string() + "' >/dev/null";
  const int rc = std::system(cmd.c_str());
  EXPECT_TRUE(WIFEXITED(rc) && WEXITSTATUS(rc) == 1) << rc;
  std::ifstream in(err);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);)
    lines.push_back(l);
  ASSERT_FALSE(lines.empty());
  EXPECT_EQ(lines.back().rfind("rgbd-simul: error: ", 0), 0u) << lines.back();
  EXPECT_NE(lines.back().find(file.string()), std::string::npos) << lines.back();
  // Bad option value: named in the message.
  const std::string cmd2 = "'" + exe + "' --output '" + (fs::path(dir) / "o").string() +
                           "' --scene kitchen 2>'" + err.string() + "' >/dev/null";
  const int rc2 = std::system(cmd2.c_str());
  EXPECT_TRUE(WIFEXITED(rc2) && WEXITSTATUS(rc2) == 1) << rc2;
  std::ifstream in2(err);
  std::string l2;
  std::getline(in2, l2);
  EXPECT_NE(l2.find("scene"), std::string::npos) << l2;
  EXPECT_FALSE(fs::exists(fs::path(dir) / "o"));
  fs::remove_all(dir);
}
