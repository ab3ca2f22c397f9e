/* A camera whose ground truth is the path of a y-up optical frame (ICL-NUIM:
 * fy < 0; rgbd-simul's ICL-like fixture "global" publishes its camera and
 * ground truth so): given as declared, the SLAM pipeline tracks it within
 * 1 cm; given with fy > 0 instead (the same images, the usual y-down frame),
 * its trajectory is the mirror image of the ground truth, which the ATE's
 * rigid alignment cannot undo and mirrored_rmse recognises. */
#include <gtest/gtest.h>
#include <roislam/io/CameraPresets.h>
#include <roislam/testing/TestData.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "PipelineRuns.h"

using roislam::testing::runOrbPipeline;

TEST(CameraAxes, AYUpGroundTruthNeedsTheCameraAsDeclared)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "global");
  const auto declared = roislam::io::loadSensorFile(seq + "/camera.ini");
  ASSERT_LT(declared.colour.fy(), 0) << "the fixture should publish a y-up camera";

  const auto asDeclared = runOrbPipeline(seq, "auto").ate;
  auto yDown = declared;
  yDown.colour.setIntrinsicParamsFromValues(
      declared.colour.fx(), -declared.colour.fy(), declared.colour.cx(), declared.colour.cy());
  const std::string dir = roislam::testing::makeTempDir("camera_axes_itest");
  const std::string file = dir + "/y-down.ini";
  std::ofstream(file) << yDown.toIniText();
  const auto mirrored = runOrbPipeline(seq, file).ate;
  std::filesystem::remove_all(dir);
  std::printf(
      "as declared (fy < 0): ATE %.4f m (mirrored %.4f); given fy > 0: ATE %.4f m (mirrored "
      "%.4f)\n",
      asDeclared.rmse, asDeclared.mirrored_rmse, mirrored.rmse, mirrored.mirrored_rmse);
  EXPECT_LT(asDeclared.rmse, 0.01);
  EXPECT_GT(mirrored.rmse, 3 * asDeclared.rmse);
  EXPECT_LT(mirrored.mirrored_rmse, 0.5 * mirrored.rmse);
}
