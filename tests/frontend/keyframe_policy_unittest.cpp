// The adaptive keyframe policy (CRgbdOdometry::TOptions::keyframe_policy =
// overlap) on ray-cast frames of a box room with known poses: the view
// overlap itself, a revisit that re-uses the keyframes made on the way out
// (the motion policy makes new ones), and a view change beyond the overlap
// threshold that makes a keyframe; and the motion policy's place limit
// (keyframe_place_limit), under which repeated passes stop adding keyframes.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <roislam/frontend/CRgbdOdometry.h>

#include <cmath>
#include <deque>
#include <string>
#include <vector>

#include "KeyframeOverlap.h"
#include "SyntheticRoom.h"

using namespace roislam::frontend;
using mrpt::poses::CPose3D;
using roislam::frontend::testing::renderRoom;
using roislam::frontend::testing::trajectoryPose;

namespace
{
CRgbdOdometry::TOptions overlapOptions()
{
  CRgbdOdometry::TOptions o;
  o.extractor.feature_type = roislam::features::EFeatureType::ORB;
  o.extractor.max_features = 500;
  o.keyframe_policy = "overlap";
  o.keyframe_translation_m = 0;
  o.keyframe_rotation_deg = 0;
  return o;
}

detail::TViewModel viewOf(const CRgbdOdometry& odo)
{
  const auto cam = roislam::frontend::testing::syntheticCamera();
  return {
      {cam.fx(), cam.fy(), cam.cx(), cam.cy()},
      cv::Size(640, 480),
      odo.options().min_depth_m,
      odo.options().max_depth_m};
}

/** A pan of 1.5 deg per frame from the room's middle (frame k's pose). */
CPose3D panPose(std::size_t k)
{
  return CPose3D(0.2, 0, 0.5, 0, 1.5 * M_PI / 180 * static_cast<double>(k), 0);
}

/** Pan frames 0..n-1, then back n-2..0 (a revisit of every view); the
 *  keyframe count after the way out and at the end. */
std::pair<std::size_t, std::size_t> thereAndBack(CRgbdOdometry& odo, std::size_t n)
{
  odo.setInitialPose(panPose(0));
  std::size_t frame = 0;
  for (std::size_t k = 0; k < n; ++k, ++frame)
    odo.process(renderRoom(panPose(k), 100, frame, 0.1 * frame));
  const std::size_t out = odo.keyframes().size();
  for (std::size_t k = n - 1; k-- > 0; ++frame)
  {
    const auto r = odo.process(renderRoom(panPose(k), 100, frame, 0.1 * frame));
    EXPECT_TRUE(r.pose.has_value());
    if (r.pose)
    {
      EXPECT_LT((*r.pose - panPose(k)).translation().norm(), 0.03) << "frame " << frame;
    }
  }
  return {out, odo.keyframes().size()};
}
}  // namespace

TEST(KeyframePolicy, ViewOverlapOfTheSameAndOfATurnedView)
{
  CRgbdOdometry odo(overlapOptions());
  odo.setInitialPose(trajectoryPose(0));
  odo.process(renderRoom(trajectoryPose(0), 100, 0, 0));
  const TKeyframe& kf = odo.keyframe(0);
  ASSERT_GT(kf.points.size(), 100u);
  const auto view = viewOf(odo);
  EXPECT_DOUBLE_EQ(detail::viewOverlap(kf, CPose3D(), view), 1.0);
  // Turned by half the horizontal field of view (62 deg at f 525 px), about
  // half of the view stays; turned round, none.
  const double half = std::atan(320.0 / 525.0);
  const double ov = detail::viewOverlap(kf, CPose3D(0, 0, 0, 0, half, 0), view);
  EXPECT_GT(ov, 0.3);
  EXPECT_LT(ov, 0.7);
  EXPECT_DOUBLE_EQ(detail::viewOverlap(kf, CPose3D(0, 0, 0, 0, M_PI, 0), view), 0.0);
  // 100 samples give about the same share as every point (binomial 1-sigma
  // 0.05).
  EXPECT_NEAR(detail::viewOverlap(kf, CPose3D(0, 0, 0, 0, half, 0), view, 100), ov, 0.1);
  // The reference candidates of a view near keyframe 0: keyframe 0.
  const auto best =
      detail::referenceCandidates(odo.keyframes(), trajectoryPose(0), view, {0.5, 0, 0}, 3, 100);
  ASSERT_EQ(best.size(), 1u);
  EXPECT_EQ(best[0], 0u);
}

TEST(KeyframePolicy, RevisitReusesKeyframes)
{
  // 30 frames pan 45 deg, most of the 62 deg field of view.
  CRgbdOdometry overlap(overlapOptions());
  const auto [out, end] = thereAndBack(overlap, 30);
  EXPECT_GE(out, 2u);
  EXPECT_EQ(end, out) << "the way back re-uses the keyframes of the way out";
  // The motion policy tracks against the newest keyframe only: the way back
  // makes new keyframes (this is what grows the soak's graph).
  auto mo = overlapOptions();
  mo.keyframe_policy = "motion";
  mo.keyframe_translation_m = 0.10;
  mo.keyframe_rotation_deg = 10;
  CRgbdOdometry motion(mo);
  const auto [outM, endM] = thereAndBack(motion, 30);
  EXPECT_GT(endM, outM);
}

/** The motion policy with keyframe_place_limit = `limit` over `passes`
 *  passes of the pan (out, back, out, ...): the keyframe count after each. */
std::vector<std::size_t> panPasses(int limit, std::size_t passes)
{
  auto o = overlapOptions();
  o.keyframe_policy = "motion";
  o.keyframe_translation_m = 0.10;
  o.keyframe_rotation_deg = 10;
  o.keyframe_place_limit = limit;
  CRgbdOdometry odo(o);
  constexpr std::size_t n = 30;
  odo.setInitialPose(panPose(0));
  std::vector<std::size_t> counts;
  std::size_t frame = 0;
  for (std::size_t p = 0; p < passes; ++p)
  {
    for (std::size_t i = p == 0 ? 0 : 1; i < n; ++i, ++frame)
    {
      const std::size_t k = p % 2 == 0 ? i : n - 1 - i;
      const auto r = odo.process(renderRoom(panPose(k), 100, frame, 0.1 * frame));
      EXPECT_TRUE(r.pose.has_value());
      if (r.pose)
      {
        EXPECT_LT((*r.pose - panPose(k)).translation().norm(), 0.03) << "frame " << frame;
      }
    }
    counts.push_back(odo.keyframes().size());
  }
  return counts;
}

TEST(KeyframePolicy, KeyframesNearArePlacesNearestFirst)
{
  std::deque<TKeyframe> kfs(4);
  const CPose3D poses[] = {
      CPose3D(0, 0, 0, 0, 0, 0), CPose3D(0.05, 0, 0, 0, 0, 0), CPose3D(0, 0, 0, 0.15, 0, 0),
      CPose3D(0.01, 0, 0, 0, 0, 0)};
  for (std::size_t i = 0; i < kfs.size(); ++i)
  {
    kfs[i].id = i;
    kfs[i].pose = poses[i];
  }
  // Bounds 0.1 m and 0.1 rad: keyframe 2 (0.15 rad) is outside; 3 is nearest.
  const auto near = detail::keyframesNear(kfs, CPose3D(0.01, 0, 0, 0, 0, 0), 0.1, 0.1);
  EXPECT_EQ(near, (std::vector<std::size_t>{3, 0, 1}));
  EXPECT_TRUE(detail::keyframesNear(kfs, CPose3D(1, 0, 0, 0, 0, 0), 0.1, 0.1).empty());
}

TEST(KeyframePolicy, PlaceLimitStopsRevisitsAddingKeyframes)
{
  // Without a limit every pass over the same views adds keyframes (the
  // motion policy measures from the newest keyframe only).
  const auto free = panPasses(0, 4);
  for (std::size_t p = 1; p < free.size(); ++p)
    EXPECT_GT(free[p], free[p - 1]) << "pass " << p;
  // With a limit of 2 a place keeps at most about two views: the last
  // passes add none, and the map stays well below the unlimited one.
  const auto limited = panPasses(2, 4);
  EXPECT_EQ(limited[0], free[0]) << "new ground is mapped as without a limit";
  EXPECT_EQ(limited[3], limited[2]);
  EXPECT_LE(limited[3], 2 * limited[0] + 1);
  EXPECT_LT(limited[3], free[3]);
}

TEST(KeyframePolicy, ViewChangeBeyondTheOverlapMakesAKeyframe)
{
  // By frame 40 (60 deg) the first view is mostly gone.
  CRgbdOdometry odo(overlapOptions());
  const auto view = viewOf(odo);
  std::vector<TFrameResult> res;
  odo.setInitialPose(panPose(0));
  for (std::size_t k = 0; k < 40; ++k)
    res.push_back(odo.process(renderRoom(panPose(k), 100, k, 0.1 * k)));
  ASSERT_GE(odo.keyframes().size(), 2u);
  for (std::size_t k = 1; k < res.size(); ++k)
  {
    const TFrameResult& r = res[k];
    ASSERT_TRUE(r.pose.has_value());
    const TKeyframe& ref = odo.keyframe(r.referenceKeyframe);
    const double ov = detail::viewOverlap(ref, *r.pose - ref.pose, view);
    // Tracked frames keep at least the threshold; keyframes are made when a
    // frame drops below it (or below the inlier count).
    if (!r.isNewKeyframe)
      EXPECT_GE(ov, odo.options().keyframe_min_overlap) << "frame " << k;
    else
      EXPECT_TRUE(
          ov < odo.options().keyframe_min_overlap ||
          static_cast<int>(r.inliers) < odo.options().keyframe_min_inliers)
          << "frame " << k << " overlap " << ov;
  }
}

TEST(KeyframePolicy, OptionsAreValidated)
{
  auto o = overlapOptions();
  o.keyframe_min_overlap = 0.6;
  o.keyframe_min_flow_inlier_share = 0.5;
  o.flow_describe_roi = "always";
  mrpt::config::CConfigFileMemory cfg;
  o.saveToConfigFile(cfg, "FrontEnd");
  CRgbdOdometry::TOptions l;
  l.loadFromConfigFile(cfg, "FrontEnd");
  EXPECT_EQ(l.keyframe_policy, "overlap");
  EXPECT_DOUBLE_EQ(l.keyframe_min_overlap, 0.6);
  EXPECT_DOUBLE_EQ(l.keyframe_min_flow_inlier_share, 0.5);
  EXPECT_EQ(l.flow_describe_roi, "always");
  EXPECT_DOUBLE_EQ(l.keyframe_rotation_deg, 0);
  const auto expectError = [](auto set, const std::string& key)
  {
    auto b = overlapOptions();
    set(b);
    try
    {
      b.validate();
      ADD_FAILURE() << key << ": expected an error";
    }
    catch (const std::invalid_argument& e)
    {
      EXPECT_NE(std::string(e.what()).find("[FrontEnd] " + key), std::string::npos) << e.what();
    }
  };
  expectError([](auto& b) { b.keyframe_policy = "sometimes"; }, "keyframe_policy");
  expectError([](auto& b) { b.keyframe_min_overlap = 1.0; }, "keyframe_min_overlap");
  expectError([](auto& b) { b.keyframe_min_overlap = -0.1; }, "keyframe_min_overlap");
  expectError([](auto& b) { b.keyframe_place_limit = -1; }, "keyframe_place_limit");
  expectError(
      [](auto& b) { b.keyframe_min_flow_inlier_share = 1.0; }, "keyframe_min_flow_inlier_share");
  expectError(
      [](auto& b) { b.keyframe_min_flow_inlier_share = -0.1; }, "keyframe_min_flow_inlier_share");
  expectError([](auto& b) { b.flow_describe_roi = "sometimes"; }, "flow_describe_roi");
  expectError([](auto& b) { b.keyframe_rotation_deg = -1; }, "keyframe_rotation_deg");
  // The motion policy needs its thresholds.
  expectError(
      [](auto& b)
      {
        b.keyframe_policy = "motion";
        b.keyframe_translation_m = 0;
      },
      "keyframe_translation_m");
}
