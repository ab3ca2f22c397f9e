/* CLandmarkScorer: TP / FP / FN / TN on constructed events with known
 * positions, ground-truth association window and interpolation. */
#include <gtest/gtest.h>
#include <mrpt/core/bits_math.h>
#include <roislam/landmarks/CLandmarkScorer.h>

using namespace roislam;
using namespace roislam::landmarks;
using Outcome = CLandmarkScorer::EOutcome;

namespace
{
/** Camera at x = t metres (moving along world x), looking along +z; 100 Hz
 *  ground truth over t in [0, 10] s, with a gap in [5, 6]. */
io::TTrajectory straightLine()
{
  io::TTrajectory gt;
  for (int i = 0; i <= 1000; ++i)
  {
    const double t = i * 0.01;
    if (t > 5.0 && t < 6.0)
      continue;
    gt.push_back({t, mrpt::poses::CPose3D(t, 0, 0, 0, 0, 0)});
  }
  return gt;
}

CLandmarkScorer::TEvent ev(double t, int32_t id, bool isNew, mrpt::math::TPoint3D p)
{
  return {static_cast<uint64_t>(t * 30), t, id, isNew, p};
}
}  // namespace

TEST(LandmarkScorer, PoseLookupWindowAndInterpolation)
{
  const CLandmarkScorer s({}, straightLine());
  ASSERT_TRUE(s.poseAt(2.005));
  EXPECT_NEAR(s.poseAt(2.005)->x(), 2.005, 1e-9);  // interpolated
  EXPECT_FALSE(s.poseAt(5.5));                     // 0.5 s from any stamp
  EXPECT_TRUE(s.poseAt(5.015));                    // 0.015 s from 5.00
  EXPECT_FALSE(s.poseAt(-1.0));
  EXPECT_TRUE(s.poseAt(10.01));

  CLandmarkScorer::TOptions o;
  o.interpolate = false;
  const CLandmarkScorer nearest(o, straightLine());
  EXPECT_NEAR(nearest.poseAt(2.004)->x(), 2.0, 1e-9);

  // Rotation is interpolated too (slerp): halfway between 0 and 90 deg yaw.
  io::TTrajectory rot{
      {0.0, mrpt::poses::CPose3D(0, 0, 0, 0, 0, 0)},
      {0.02, mrpt::poses::CPose3D(0, 0, 0, mrpt::DEG2RAD(90.0), 0, 0)}};
  const CLandmarkScorer r({}, rot);
  EXPECT_NEAR(r.poseAt(0.01)->yaw(), mrpt::DEG2RAD(45.0), 1e-9);
}

TEST(LandmarkScorer, CountsTruePositivesFalsePositivesAndDuplicates)
{
  const CLandmarkScorer s({}, straightLine());
  // World positions = camera x + optical x.
  const std::vector<CLandmarkScorer::TEvent> events{
      ev(1.0, 0, true, {0.0, 0, 2}),    // L0 at world x=1.0: TN (first)
      ev(1.5, 0, false, {-0.4, 0, 2}),  // ROI at 1.1: 0.1 m from L0 -> TP
      ev(2.0, 1, true, {1.0, 0, 2}),    // L1 at 3.0: TN
      ev(2.5, 0, false, {0.5, 0, 2}),   // ROI at 3.0 recalled as L0 (1.0): FP
      ev(3.0, 2, true, {0.1, 0, 2}),    // L2 at 3.1, within 0.25 of L1: FN
      ev(3.2, 1, false, {-0.1, 0, 2}),  // ROI at 3.1, 0.1 from L1: TP
      ev(5.5, 1, false, {0, 0, 2}),     // no ground truth: unscored
      ev(4.0, 3, true, {1.0, 0, 2}),    // L3 at 5.0: TN
      ev(7.0, 3, false, {-2.0, 0, 2}),  // ROI at 5.0: TP
      CLandmarkScorer::TEvent{210, 7.0, 3, false, std::nullopt},  // no depth: unscored
  };
  const auto score = s.score(events);
  EXPECT_EQ(score.truePositives, 3);
  EXPECT_EQ(score.falsePositives, 1);
  EXPECT_EQ(score.falseNegatives, 1);
  EXPECT_EQ(score.trueNegatives, 3);
  EXPECT_EQ(score.unscored, 2);
  ASSERT_TRUE(score.precision);
  EXPECT_NEAR(*score.precision, 3.0 / 4.0, 1e-12);
  ASSERT_TRUE(score.recall);
  EXPECT_NEAR(*score.recall, 3.0 / 4.0, 1e-12);
  ASSERT_EQ(score.outcomes.size(), events.size());
  EXPECT_EQ(score.outcomes[1], Outcome::TruePositive);
  EXPECT_EQ(score.outcomes[3], Outcome::FalsePositive);
  EXPECT_EQ(score.outcomes[4], Outcome::FalseNegative);
  EXPECT_EQ(score.outcomes[6], Outcome::Unscored);
  EXPECT_STREQ(toString(score.outcomes[4]), "FN");
}

TEST(LandmarkScorer, RadiusIsConfigurableAndEmptyGivesNoRatios)
{
  CLandmarkScorer::TOptions o;
  o.match_radius = 0.05;
  const CLandmarkScorer s(o, straightLine());
  const auto score =
      s.score({ev(1.0, 0, true, {0, 0, 2}), ev(1.5, 0, false, {-0.4, 0, 2})});  // 0.1 m apart
  EXPECT_EQ(score.falsePositives, 1);
  EXPECT_EQ(score.truePositives, 0);
  EXPECT_NEAR(*score.precision, 0.0, 1e-12);
  EXPECT_FALSE(score.recall);  // TP + FN = 0

  const auto empty = s.score({});
  EXPECT_FALSE(empty.precision);
  EXPECT_FALSE(empty.recall);
}

TEST(LandmarkScorer, RecallOfAnUnscorableLandmarkIsUnscored)
{
  const CLandmarkScorer s({}, straightLine());
  const auto score = s.score({ev(5.5, 0, true, {0, 0, 2}), ev(6.5, 0, false, {0, 0, 2})});
  EXPECT_EQ(score.unscored, 2);
  EXPECT_EQ(score.truePositives + score.falsePositives, 0);
}
