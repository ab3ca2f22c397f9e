/* An error common to all keypoints of a frame, reproduced with rgbd-simul:
 * each frame's colour image shifted as a whole (common_shift_px, which the
 * sequence's camera.ini records as common_pixel_sigma_px). Registrations
 * average their keypoints' own noise down but not the shift, so edges that
 * ignore it claim far too much (fr1's symptom: chi² in the hundreds against
 * the ground truth); with the sensor's value their chi² is honest again and
 * the trajectory more accurate. */
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFile.h>
#include <roislam/evaluation/CTrajectoryEvaluator.h>
#include <roislam/evaluation/EdgeChi2.h>
#include <roislam/graphslam/CSlamPipeline.h>
#include <roislam/graphslam/SensorFacts.h>
#include <roislam/io/TumTrajectory.h>
#include <roislam/sim/CRgbdSimulator.h>
#include <roislam/testing/TestData.h>

#include <cstdio>

namespace graphslam = roislam::graphslam;

namespace
{
struct TRunFigures
{
  double ate = 0, chi2Median = 0;
};

TRunFigures run(const std::string& seq, double modelCommonPx)
{
  graphslam::CSlamContext::TConfig cfg;
  cfg.frontEnd.extractor.feature_type = roislam::features::EFeatureType::ORB;
  cfg.frontEnd.extractor.max_features = 600;
  cfg.backEnd.edge_information = "estimator";
  auto source = roislam::io::CFrameSource::open(seq);
  // The camera's facts as the apps apply them, then the shift under test.
  graphslam::applySensorFacts(cfg.frontEnd, source->sensor(), false, "test", "", {});
  cfg.frontEnd.common_pixel_sigma_px = modelCommonPx;
  const auto gt = roislam::io::loadTumTrajectory(*source->groundTruthFile());
  graphslam::CSlamPipeline p(cfg, std::move(source));
  while (p.step())
  {
  }
  p.finish();
  TRunFigures f;
  f.ate = roislam::evaluation::CTrajectoryEvaluator().evaluate(gt, p.trajectory()).ate.rmse;
  const auto& keyframes = p.context().odometry().keyframes();
  const auto chi2 = roislam::evaluation::edgeChi2(
      p.graph(), [&](mrpt::graphs::TNodeID id) { return keyframes.at(id).timestamp; }, gt);
  EXPECT_TRUE(chi2);
  if (chi2)
    f.chi2Median = chi2->median;
  std::printf(
      "model %.2f px: ATE %.4f m, edge chi2 median %.2f\n", modelCommonPx, f.ate, f.chi2Median);
  return f;
}
}  // namespace

TEST(CommonShift, EdgesCarryTheShiftTheCameraDescribes)
{
  // rgbd-simul's ICL-like camera (global shutter, disparity noise), 1 px of
  // common shift per frame and axis.
  roislam::sim::CRgbdSimulator::TOptions o;
  o.loadFromConfigFile(
      mrpt::config::CConfigFile(roislam::testing::sourceDir() + "/config/rgbd-simul-icl.ini"),
      "RgbdSimulator");
  o.frames = 90;
  o.seed = 5;
  o.commonShiftPx = 1.0;
  const roislam::testing::CTempDir dir("common_shift");
  const std::string seq = dir.path() + "/seq";
  {
    roislam::sim::CRgbdSimulator sim(o);
    sim.writeSequence(seq);
  }
  // The camera describes its shift.
  EXPECT_DOUBLE_EQ(
      roislam::io::CFrameSource::open(seq)->sensor().sensor.common_pixel_sigma_px, 1.0);

  const TRunFigures ignored = run(seq, 0.0), carried = run(seq, 1.0);
  const double expectedMedian = 5.35;  // of chi²(6)
  EXPECT_GT(ignored.chi2Median, 4 * expectedMedian);
  EXPECT_GT(carried.chi2Median, expectedMedian / 2);
  EXPECT_LT(carried.chi2Median, expectedMedian * 2);
  EXPECT_LT(carried.ate, ignored.ate);
  EXPECT_LT(carried.ate, 0.01);
}
