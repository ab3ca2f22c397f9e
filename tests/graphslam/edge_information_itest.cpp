/* A global-shutter synthetic loop (rgbd-simul's ICL-like camera: no rolling
 * shutter, no distortion, disparity depth noise; ctest fixture "global"):
 * the SLAM pipeline with its camera facts (0 ms readout, the disparity noise
 * model) tracks it within 1 cm, and with [GraphSlam] edge_information =
 * estimator its graph edges are honest: their chi² against the ground
 * truth's relative poses has a median within a factor of 2 of chi²(6)'s. */
#include <gtest/gtest.h>
#include <roislam/evaluation/CTrajectoryEvaluator.h>
#include <roislam/evaluation/EdgeChi2.h>
#include <roislam/graphslam/CSlamPipeline.h>
#include <roislam/io/TumTrajectory.h>
#include <roislam/testing/TestData.h>

#include <cstdio>

namespace graphslam = roislam::graphslam;

TEST(EdgeInformation, GlobalShutterLoopIsAccurateAndItsEdgesHonest)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "global");
  graphslam::CSlamContext::TConfig cfg;
  cfg.frontEnd.extractor.feature_type = roislam::features::EFeatureType::ORB;
  cfg.frontEnd.extractor.max_features = 600;
  cfg.frontEnd.rolling_shutter_ms = 0;
  cfg.frontEnd.depth_noise.model = "disparity";  // rgbd-simul's defaults otherwise
  cfg.backEnd.edge_information = "estimator";
  auto source = roislam::io::CFrameSource::open(seq);
  const auto gt = roislam::io::loadTumTrajectory(*source->groundTruthFile());
  graphslam::CSlamPipeline p(cfg, std::move(source));
  while (p.step())
  {
  }
  p.finish();
  const double ate =
      roislam::evaluation::CTrajectoryEvaluator().evaluate(gt, p.trajectory()).ate.rmse;
  const auto& keyframes = p.context().odometry().keyframes();
  const auto chi2 = roislam::evaluation::edgeChi2(
      p.graph(), [&](mrpt::graphs::TNodeID id) { return keyframes.at(id).timestamp; }, gt);
  ASSERT_TRUE(chi2);
  std::printf(
      "ATE %.4f m, %zu keyframes, %zu loop closures; edge chi2 over %zu edges: median %.2f, "
      "mean %.2f\n",
      ate, keyframes.size(), p.context().loopClosures().size(), chi2->edges, chi2->median,
      chi2->mean);
  EXPECT_LT(ate, 0.01);
  EXPECT_GT(chi2->edges, keyframes.size());
  const double expectedMedian = 5.35;  // of chi²(6)
  EXPECT_GT(chi2->median, expectedMedian / 2);
  EXPECT_LT(chi2->median, expectedMedian * 2);
}
