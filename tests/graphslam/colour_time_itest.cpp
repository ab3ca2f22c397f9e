/* The fr1 description's colour_time_offset_ms (-7 ms) against the shared
 * data: on both fr1 excerpts, traditional ORB's trajectory, stamped as the
 * frame sources now stamp it, agrees better with the ground truth's rotation
 * (the benchmark's RPE, 1 s pairs) than the same poses at their raw stamps
 * (+7 ms) or with the offset applied twice (-7 ms more). The poses do not
 * depend on the offset: only when they are said to be. Prints the figures;
 * skips when the shared data are absent. */
#include <gtest/gtest.h>
#include <roislam/common/ProcessTuning.h>
#include <roislam/evaluation/CTrajectoryEvaluator.h>
#include <roislam/graphslam/CRoiGraphSlamApp.h>
#include <roislam/io/CameraPresets.h>
#include <roislam/io/TumTrajectory.h>
#include <roislam/testing/TestData.h>

#include <cstdio>
#include <filesystem>
#include <string>

namespace fs = std::filesystem;
using roislam::evaluation::CTrajectoryEvaluator;
using roislam::graphslam::CRoiGraphSlamApp;

namespace
{
/** Rotation RPE (deg) of `est` with `offsetS` added to its stamps. */
double rotationRpe(
    const roislam::io::TTrajectory& gt, const roislam::io::TTrajectory& est, double offsetS)
{
  CTrajectoryEvaluator::TOptions o;
  o.offset = offsetS;
  return CTrajectoryEvaluator(o).evaluate(gt, est).rpe.rot_rmse_deg;
}

void expectStampsAsTaken(const std::string& seq)
{
  roislam::common::tuneAllocatorForImages();
  CRoiGraphSlamApp::TArguments a;
  a.iniFile = roislam::testing::sourceDir() + "/config/traditional.ini";
  a.input = seq;
  a.camera = "fr1";
  a.outputDir = roislam::testing::makeTempDir("gs_colour_time");
  a.feature = "orb";
  a.maxFeatures = 600;
  a.snapshot = false;
  const auto s = CRoiGraphSlamApp(a).run();
  ASSERT_FALSE(s.failed);
  const auto est = roislam::io::loadTumTrajectory(a.outputDir + "/trajectory.txt");
  const auto gt = roislam::io::loadTumTrajectory(seq + "/groundtruth.txt");
  fs::remove_all(a.outputDir);

  const double offsetS = roislam::io::sensorPreset("fr1").colour_time_offset_ms * 1e-3;
  ASSERT_LT(offsetS, 0);
  const double asTaken = rotationRpe(gt, est, 0);
  const double raw = rotationRpe(gt, est, -offsetS);
  const double twice = rotationRpe(gt, est, offsetS);
  std::printf(
      "%s: rotation RPE %.3f deg as stamped (%+.0f ms), %.3f at the raw stamps, %.3f with "
      "the offset twice\n",
      fs::path(seq).filename().c_str(), asTaken, offsetS * 1e3, raw, twice);
  EXPECT_LT(asTaken, raw);
  EXPECT_LT(asTaken, twice);
}
}  // namespace

TEST(ColourTime, Fr1TrajectoriesAreStampedWhenTheImagesWereTaken)
{
  ROISLAM_REQUIRE_SHARED_TUM(rpy);
  expectStampsAsTaken(rpy);
  const fs::path xyz = fs::path(rpy).parent_path() / "rgbd_dataset_freiburg1_xyz_first150";
  if (!fs::exists(xyz / "rgb.txt"))
    GTEST_SKIP() << "fr1/xyz excerpt not found beside " << rpy;
  expectStampsAsTaken(xyz.string());
}
