/* Keyframes where the features never were (README "Keyframes where the
 * features never were"), end to end on rgbd-simul's furnished featureless
 * room behind the ICL-like camera (fixture "featureless_furnished"). Its only
 * features lie on shading edges: SIFT registers a frame with 15-37 inliers,
 * below keyframe_min_inliers, and the ROI modes' regions fail on every frame.
 * Both used to make nearly every frame a keyframe, and the chain of those
 * edges drifted where depth ICP, carrying the registrations, is right to
 * half a millimetre. The keyframe policy now takes a count below the floor
 * as news only where the keyframe's registrations reached it, and a failed
 * ROI only where depth ICP does not carry the frame. */
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFile.h>
#include <roislam/testing/TestData.h>

#include <cstdio>
#include <string>

#include "PipelineRuns.h"

namespace
{
roislam::testing::TPipelineRun run(
    const std::string& seq, const std::string& mode, const char* feature)
{
  const std::string ini = roislam::testing::sourceDir() + "/config/" + mode + ".ini";
  auto cfg = roislam::graphslam::CSlamContext::loadConfig(mrpt::config::CConfigFile(ini), ini);
  cfg.frontEnd.extractor.feature_type = roislam::features::featureTypeFromString(feature);
  cfg.frontEnd.extractor.max_features = 600;
  return roislam::testing::runPipeline(seq, "auto", cfg);
}

/** Before the policy changed, the 90 frames made 30 (traditional SIFT), 72
 *  (big ROI ORB) and 73 (small ROI SIFT) keyframes, with ATE 1.81, 2.21 and
 *  4.78 mm; after it, 23, 30 and 34, with 1.81, 2.05 and 6.74 mm. Over 300
 *  frames of the same room the fewer keyframes pay (README); over these 90
 *  the gain does not show (small ROI SIFT is worse), so the ATE is bounded
 *  loosely. Since depth ICP joins before its scale is measured (stop 52):
 *  23, 30 and 32 keyframes, 1.20, 1.49 and 6.45 mm; and since a keyframe
 *  without a ROI makes none on a failed one: 23, 30 and 27, 1.20, 1.49 and
 *  2.19 mm; and since frames that follow anchors count below the floor
 *  only where such a frame reached it (stop 53): 23, 22 and 25, 1.20, 1.07
 *  and 2.53 mm. */
void expectFewKeyframes(
    const std::string& seq, const std::string& mode, const char* feature, double maxShare,
    double maxAte)
{
  const auto r = run(seq, mode, feature);
  const auto& s = r.frontEndStats;
  std::printf(
      "%s %s: %zu keyframes of %zu frames (%zu whole-image fallbacks, %zu ICP-refined), ATE "
      "%.2f mm\n",
      mode.c_str(), feature, s.keyframes, s.frames, s.fullImageFallback, s.icpRefined,
      r.ate.rmse * 1000);
  EXPECT_LT(static_cast<double>(s.keyframes), maxShare * static_cast<double>(s.frames));
  EXPECT_LT(r.ate.rmse, maxAte);
}
}  // namespace

TEST(FeaturelessKeyframes, FewInliersAreNoNewsWhereTheKeyframeNeverHadMore)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "featureless_furnished");
  expectFewKeyframes(seq, "traditional", "sift", 0.3, 0.003);
}

TEST(FeaturelessKeyframes, AFailingRoiIsNoNewsWhereDepthIcpCarriesTheFrame)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "featureless_furnished");
  expectFewKeyframes(seq, "roi_big", "orb", 0.4, 0.003);
  expectFewKeyframes(seq, "roi_small", "sift", 0.4, 0.01);
}

/** Nor where the reference keyframe found no ROI (stop 52): the room's
 *  keyframes have none, and small ROI SIFT made 32 keyframes (ATE 6.45 mm)
 *  with fallbacks of 15-17 inliers before, 27 (2.19 mm) after. */
TEST(FeaturelessKeyframes, ARoiTheKeyframeNeverHadCannotWearOut)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "featureless_furnished");
  expectFewKeyframes(seq, "roi_small", "sift", 0.33, 0.004);
}

/** A frame that follows its keyframe's anchors counts below the floor only
 *  where a registration against that keyframe reached it (stop 53), as for
 *  described features. Counting the anchors instead (20-30 on the room's
 *  shading edges, of which flow keeps 18-25) made big ROI ORB 30 keyframes
 *  (ATE 1.49 mm), most of them in a row; now 22 (1.07 mm). */
TEST(FeaturelessKeyframes, FlowBelowTheFloorIsNoNewsWhereNoFrameReachedIt)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "featureless_furnished");
  expectFewKeyframes(seq, "roi_big", "orb", 0.28, 0.002);
}
