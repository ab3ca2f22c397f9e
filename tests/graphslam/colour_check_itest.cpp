/* The colour image as the arbiter between features and depth ICP
 * (icp_colour_check, libs/frontend/src/PhotometricCheck.h), end to end on
 * rgbd-simul's furnished featureless room behind the ICL-like camera
 * (fixture "featureless_furnished"): SIFT finds a few dozen features on the
 * shading edges, registrations that are confidently wrong, while depth ICP
 * is right. Without the check, measured fusion books the disagreement
 * against ICP and the features win; with it, the colour sides with ICP. */
#include <gtest/gtest.h>
#include <roislam/testing/TestData.h>

#include <cstdio>
#include <string>

#include "PipelineRuns.h"

namespace
{
struct TRun
{
  double ate = 0;
  std::size_t overruled = 0, refined = 0;
};

TRun runSift(const std::string& seq, bool colourCheck)
{
  roislam::graphslam::CSlamContext::TConfig cfg;
  cfg.frontEnd.extractor.feature_type = roislam::features::EFeatureType::SIFT;
  cfg.frontEnd.extractor.max_features = 600;
  cfg.frontEnd.icp_colour_check = colourCheck;
  const auto run = roislam::testing::runPipeline(seq, "auto", cfg);
  return {run.ate.rmse, run.frontEndStats.icpOverruledFeatures, run.frontEndStats.icpRefined};
}
}  // namespace

TEST(ColourCheck, AFeaturelessRoomFollowsDepthIcpWhereTheColourSaysSo)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "featureless_furnished");
  const TRun on = runSift(seq, true);
  const TRun off = runSift(seq, false);
  std::printf(
      "SIFT, traditional: colour check on: ATE %.2f mm (%zu of %zu ICP-refined frames "
      "overruled the features); off: %.2f mm\n",
      on.ate * 1000, on.overruled, on.refined, off.ate * 1000);
  EXPECT_EQ(off.overruled, 0u);
  EXPECT_GE(on.overruled, 5u);
  EXPECT_LT(on.ate, 0.005);
  EXPECT_GT(off.ate, 2 * on.ate);
}
