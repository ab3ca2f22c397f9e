/* A sequence in Microsoft 7-Scenes' own layout (rgbd-simul's
 * config/rgbd-simul-7scenes.ini; ctest fixture "sevenscenes"): no lists, no
 * timestamps, no camera.ini, depth NOT registered to colour and the depth
 * camera's poses as ground truth. `--camera auto` picks the 7scenes preset,
 * the reader registers the depth into the colour camera and turns the poses
 * into the colour camera's, and the SLAM pipeline tracks it within 1 cm.
 * Read as if its depth were registered (the same cameras otherwise), it
 * does markedly worse: the registration is what makes it work. */
#include <gtest/gtest.h>
#include <roislam/io/CameraPresets.h>
#include <roislam/testing/TestData.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "PipelineRuns.h"

TEST(SevenScenes, UnregisteredDepthInItsOwnLayoutIsTrackedWithinACentimetre)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "sevenscenes");
  const auto run = roislam::testing::runOrbPipeline(seq, "auto");
  EXPECT_EQ(run.sensorSource, "preset 7scenes");
  const double registered = run.ate.rmse;

  auto asIs = roislam::io::sensorPreset("7scenes");
  asIs.depth_registered = true;
  const std::string dir = roislam::testing::makeTempDir("seven_scenes_itest");
  const std::string file = dir + "/as-is.ini";
  std::ofstream(file) << asIs.toIniText();
  const double unregistered = roislam::testing::runOrbPipeline(seq, file).ate.rmse;
  std::filesystem::remove_all(dir);
  std::printf(
      "7-Scenes layout, ORB: ATE %.4f m with the depth registered, %.4f m read as it is\n",
      registered, unregistered);
  EXPECT_LT(registered, 0.01);
  EXPECT_GT(unregistered, 1.5 * registered);
}
