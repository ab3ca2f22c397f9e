// CRgbdOdometry on ray-cast RGB-D frames of a box room with known poses:
// feature tracking accuracy, ROI fallback vs strict ROI, depth-ICP and
// constant-velocity fallbacks on a featureless room, keyframe registration,
// back-end pose updates and option handling.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <roislam/frontend/CRgbdOdometry.h>
#include <roislam/testing/TestData.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <opencv2/imgproc.hpp>
#include <string>
#include <utility>
#include <vector>

#include "SyntheticRoom.h"

using namespace roislam::frontend;
using mrpt::poses::CPose3D;
using roislam::frontend::testing::renderRoom;
using roislam::frontend::testing::trajectoryPose;

namespace
{
double transErr(const CPose3D& a, const CPose3D& b)
{
  return (a - b).translation().norm();
}
double rotErrDeg(const CPose3D& a, const CPose3D& b)
{
  const Eigen::Matrix3d R = (a - b).getRotationMatrix().asEigen();
  return Eigen::AngleAxisd(R).angle() * 180.0 / M_PI;
}

CRgbdOdometry::TOptions baseOptions()
{
  CRgbdOdometry::TOptions o;
  o.extractor.feature_type = roislam::features::EFeatureType::ORB;
  o.extractor.max_features = 500;
  return o;
}

// Runs n frames; returns the results. Poses start at trajectoryPose(0).
std::vector<TFrameResult> run(CRgbdOdometry& odo, double contrast, std::size_t n)
{
  odo.setInitialPose(trajectoryPose(0));
  std::vector<TFrameResult> out;
  for (std::size_t k = 0; k < n; ++k)
    out.push_back(odo.process(renderRoom(trajectoryPose(k), contrast, k, 0.1 * k)));
  return out;
}
}  // namespace

TEST(RgbdOdometry, TracksTexturedRoomWithFeatures)
{
  CRgbdOdometry odo(baseOptions());
  const auto res = run(odo, 100, 16);
  EXPECT_EQ(res[0].method, ETrackingMethod::Initial);
  EXPECT_TRUE(res[0].isNewKeyframe);
  for (std::size_t k = 1; k < res.size(); ++k)
  {
    ASSERT_EQ(res[k].method, ETrackingMethod::Features) << "frame " << k;
    ASSERT_TRUE(res[k].pose.has_value());
    // The block texture's axis-aligned corners bias keypoints by ~1 px in a
    // common direction (~5 mm at 2.5 m): bounds leave room for that.
    EXPECT_LT(transErr(*res[k].pose, trajectoryPose(k)), 0.02) << "frame " << k;
    EXPECT_LT(rotErrDeg(*res[k].pose, trajectoryPose(k)), 0.5) << "frame " << k;
    EXPECT_GE(res[k].inliers, 50u);
  }
  // 0.016 m/frame and 0.45 deg/frame: keyframes about every 6 frames.
  EXPECT_GE(odo.keyframes().size(), 2u);
  EXPECT_EQ(odo.stats().features, res.size() - 1);
  // A new keyframe's first constraint is the odometry edge from its reference.
  for (const auto& r : res)
    if (r.isNewKeyframe && r.newKeyframeId > 0)
    {
      ASSERT_FALSE(r.constraints.empty());
      EXPECT_EQ(r.constraints[0].fromKeyframe, r.referenceKeyframe);
      EXPECT_EQ(r.constraints[0].toKeyframe, r.newKeyframeId);
      const auto& kfA = odo.keyframe(r.constraints[0].fromKeyframe);
      EXPECT_LT(transErr(kfA.pose + r.constraints[0].relativePose, *r.pose), 1e-9);
      // Information: symmetric positive definite.
      const Eigen::Matrix<double, 6, 6> I = r.constraints[0].information.asEigen();
      EXPECT_LT((I - I.transpose()).norm(), 1e-6 * I.norm());
      EXPECT_GT(I.selfadjointView<Eigen::Lower>().eigenvalues().minCoeff(), 0.0);
    }
  // Keyframes store only features with depth, with their 3-D points.
  const auto& kf0 = odo.keyframe(0);
  ASSERT_GT(kf0.features.size(), 100u);
  EXPECT_EQ(kf0.points.size(), kf0.features.size());
  EXPECT_EQ(kf0.pixels.size(), kf0.features.size());
  EXPECT_THROW(odo.keyframe(1000), std::out_of_range);
}

TEST(RgbdOdometry, PoorlyDeterminedRegistrationsAreCombinedWithDepthIcp)
{
  // Gate below any registration's uncertainty: every feature registration is
  // combined with ICP and must stay as accurate; gate off: none is.
  for (const double gate : {1e-9, 0.0})
  {
    SCOPED_TRACE(gate);
    auto o = baseOptions();
    o.icp_refine_sigma_m = gate;
    CRgbdOdometry odo(o);
    const auto res = run(odo, 100, 10);
    for (std::size_t k = 1; k < res.size(); ++k)
    {
      ASSERT_EQ(res[k].method, ETrackingMethod::Features) << "frame " << k;
      EXPECT_EQ(res[k].icpRefined, gate > 0) << "frame " << k;
      EXPECT_LT(transErr(*res[k].pose, trajectoryPose(k)), 0.02) << "frame " << k;
      EXPECT_LT(rotErrDeg(*res[k].pose, trajectoryPose(k)), 0.5) << "frame " << k;
    }
    EXPECT_EQ(odo.stats().icpRefined, gate > 0 ? res.size() - 1 : 0u);
  }
}

namespace
{
/** Frame k of the room seen from pose, with its depth taken at that pose
 *  (consistent) or at a pose off by a few centimetres / tenths of a degree
 *  that change from frame to frame (depth biased against colour, as on a
 *  Kinect whose depth and colour are not captured together). */
roislam::io::TRGBDFrame roomFrame(const CPose3D& pose, std::size_t k, bool depthConsistent)
{
  auto f = renderRoom(pose, 100, k, 0.1 * k);
  if (!depthConsistent)
  {
    const double x = static_cast<double>(k);
    const CPose3D off(
        0.02 * std::sin(1.3 * x), 0.015 * std::cos(1.7 * x), 0.02 * std::sin(0.9 * x),
        0.006 * std::sin(2.3 * x), 0.006 * std::cos(1.1 * x), 0);
    f.depth = renderRoom(pose + off, 100, k, 0.1 * k).depth;
  }
  return f;
}
}  // namespace

TEST(RgbdOdometry, MeasuredIcpFusionFollowsHowWellDepthAgreesWithColour)
{
  // icp_fusion = measured: where depth agrees with colour, ICP joins every
  // registration once its scale is known (10 comparisons) and the poses are
  // as accurate as the features alone; where it does not, the scale grows,
  // ICP only probes every icp_probe_interval registrations and fuses none
  // of the well-determined ones, so the poses are those of the features,
  // and the probes pair a quarter of the cells. Before the scale is known,
  // ICP joins the well-determined registrations it agrees with at the
  // unverified ICP's scale: those of consistent depth (9 frames here), none
  // of biased depth.
  const std::size_t n = 36, warmUp = 12;
  for (const bool consistent : {true, false})
  {
    SCOPED_TRACE(consistent ? "consistent depth" : "biased depth");
    double err[2] = {0, 0};
    std::size_t ran = 0, fused = 0;
    // Well-determined registrations fused before the scale was measured (at
    // the unverified ICP's scale; before stop 52 none were).
    std::size_t fusedUnmeasured = 0;
    std::vector<double> shares;  // of the ICP runs' pairs
    std::vector<double> scales;  // measured fusion's k after each comparison
    // The joint fit of both scales, once a window of 30 comparisons is held:
    // how many frames reported one, the last, and the run's stats.
    std::size_t jointReports = 0;
    double lastFeatureScale = 0, statsFeatureScale = 0;
    for (const std::string fusion : {"weak", "measured"})
    {
      auto o = baseOptions();
      o.icp_fusion = fusion;
      CRgbdOdometry odo(o);
      odo.setInitialPose(trajectoryPose(0));
      for (std::size_t k = 0; k < n; ++k)
      {
        const auto r = odo.process(roomFrame(trajectoryPose(k), k, consistent));
        ASSERT_TRUE(r.pose.has_value()) << "frame " << k;
        if (fusion == "measured" && r.icpRefined && r.icpScale == 0)
          ++fusedUnmeasured;
        if (fusion == "measured" && r.featureScale > 0)
        {
          ++jointReports;
          lastFeatureScale = r.featureScale;
          EXPECT_GT(r.icpJointScale, 0.0);
        }
        if (k < warmUp)
          continue;
        err[fusion == "measured"] += transErr(*r.pose, trajectoryPose(k)) / (n - warmUp);
        if (fusion != "measured" || r.isNewKeyframe)
          continue;
        ran += r.times.icp_ms > 0 ? 1 : 0;
        fused += r.icpRefined ? 1 : 0;
        if (r.icpPairShare > 0)
          shares.push_back(r.icpPairShare);
        if (r.icpScale > 0)
          scales.push_back(r.icpScale);
        else
          EXPECT_EQ(r.times.icp_ms, 0.0) << "frame " << k << ": ICP ran, no scale reported";
      }
      if (fusion == "measured")
        statsFeatureScale = odo.stats().featureScale.value_or(0.0);
    }
    // Consistent depth compares every frame, so the window fills; biased
    // depth only probes, and never does. The run's stats keep the last fit.
    if (consistent)
      EXPECT_GT(jointReports, 0u);
    else
      EXPECT_EQ(jointReports, 0u);
    EXPECT_EQ(statsFeatureScale, lastFeatureScale);
    const std::size_t frames = n - warmUp;
    if (consistent)
    {
      EXPECT_EQ(fused, ran);
      EXPECT_GE(fused, frames - frames / 4);
      EXPECT_LT(err[1], 1.1 * err[0] + 1e-3);
      EXPECT_GE(fusedUnmeasured, 5u);
    }
    else
    {
      EXPECT_LE(ran, frames / 10 + 2);
      EXPECT_EQ(fused, 0u);
      EXPECT_LT(err[1], 1.1 * err[0] + 1e-3);
      EXPECT_EQ(fusedUnmeasured, 0u);
    }
    // Depth that agrees: ICP's error is noise, every pair counts. Biased
    // depth: its error is a bias (k >= 12), so the probes pair a quarter of
    // the cells (IcpConsistency.h's model).
    ASSERT_FALSE(shares.empty());
    for (const double q : shares)
      EXPECT_DOUBLE_EQ(q, consistent ? 1.0 : 0.25);
    // The scale each frame reports (frames.csv icp_scale) says the same:
    // about 1 where depth agrees, at least 12 where it is biased.
    ASSERT_FALSE(scales.empty());
    for (const double k : scales)
      if (consistent)
        EXPECT_LT(k, 12.0);
      else
        EXPECT_GE(k, 12.0);
    std::printf(
        "%s depth: mean error weak %.4f m, measured %.4f m; ICP ran on %zu, fused into %zu of %zu "
        "ordinary frames; fused before the scale was measured: %zu\n",
        consistent ? "consistent" : "biased", err[0], err[1], ran, fused, frames, fusedUnmeasured);
  }
}

namespace
{
/** A camera that goes back and forth along the first 18 poses of the test
 *  trajectory (its pose k), so that a long run stays in the room. */
CPose3D backAndForthPose(std::size_t k)
{
  const std::size_t phase = k % 36;
  return trajectoryPose(phase <= 18 ? phase : 36 - phase);
}
}  // namespace

TEST(RgbdOdometry, IcpProbesFollowAScaleThatChanges)
{
  // The scale of ICP's covariance changes within a run (on the fr1 Kinect
  // the depth's disagreement with colour follows the motion: fr1/rpy reads
  // 63-196 from its first 10 comparisons, a median of 15-36 over the run). Here depth is biased
  // against colour over the first frames, which sets a large scale: ICP only
  // probes, every icp_probe_interval registrations. Once depth agrees, the
  // probes turn the window of 30 comparisons over, the scale falls and ICP
  // is fused into every registration again. Before stop 54 the interval
  // doubled after each probe, up to 8x: the window kept the first frames'
  // comparisons, the scale stayed, and ICP was not fused again in this run.
  const std::size_t n = 170, biasedUntil = 12, tail = 20;
  auto o = baseOptions();
  o.icp_fusion = "measured";
  CRgbdOdometry odo(o);
  odo.setInitialPose(backAndForthPose(0));
  double scaleWhileBiased = 0, lastScale = 0;
  std::size_t probes = 0, tailRan = 0, tailFused = 0;
  for (std::size_t k = 0; k < n; ++k)
  {
    const auto r = odo.process(roomFrame(backAndForthPose(k), k, k >= biasedUntil));
    ASSERT_TRUE(r.pose.has_value()) << "frame " << k;
    if (r.icpScale > 0)
      lastScale = r.icpScale;
    if (k == biasedUntil - 1)
      scaleWhileBiased = lastScale;
    if (k >= biasedUntil && r.times.icp_ms > 0 && r.icpPairShare < 1)
      ++probes;
    // Frames registered against a keyframe whose depth map is no longer
    // held (the camera came back to an older one) do not run ICP.
    if (k + tail >= n && !r.isNewKeyframe && r.times.icp_ms > 0)
    {
      ++tailRan;
      tailFused += r.icpRefined ? 1 : 0;
    }
  }
  // Biased depth: a scale of at least 12, as in the test above, then probes
  // on a quarter of the pairs.
  EXPECT_GE(scaleWhileBiased, 12.0);
  EXPECT_GE(probes, 5u);
  // Depth that agrees: the scale of consistent depth, and ICP runs on and
  // is fused into the ordinary registrations of the last frames.
  EXPECT_LT(lastScale, 12.0);
  EXPECT_GE(tailRan, tail / 2);
  EXPECT_EQ(tailFused, tailRan);
  std::printf(
      "scale %.1f while biased, %.2f at the end; %zu probes on a quarter of the pairs; ICP fused "
      "into %zu of the %zu ordinary frames of the last %zu that ran it\n",
      scaleWhileBiased, lastScale, probes, tailFused, tailRan, tail);
}

TEST(RgbdOdometry, RegisterKeyframesAndCorrectKeyframePoses)
{
  auto o = baseOptions();
  o.keyframe_translation_m = 0.03;
  CRgbdOdometry odo(o);
  run(odo, 100, 8);
  ASSERT_GE(odo.keyframes().size(), 3u);
  const auto& a = odo.keyframe(0);
  const auto& b = odo.keyframe(2);
  const auto e = odo.registerKeyframes(0, 2);
  ASSERT_TRUE(e.has_value());
  const CPose3D truthRel = trajectoryPose(b.frameIndex) - trajectoryPose(a.frameIndex);
  EXPECT_LT(transErr(e->pose, truthRel), 0.02);
  EXPECT_LT(rotErrDeg(e->pose, truthRel), 0.5);
  EXPECT_GT(e->inliers, 50u);
  EXPECT_LT(e->rmse_px, 2.0);

  // The back end moves the last keyframe: the next frame follows it.
  const std::size_t last = odo.keyframes().size() - 1;
  const CPose3D shift(0.5, 0, 0, 0, 0, 0);
  odo.correctKeyframePoses({{last, shift + odo.keyframe(last).pose}, {999, CPose3D()}});
  EXPECT_EQ(odo.keyframes().size(), last + 1);  // unknown ids are ignored
  const auto r = odo.process(renderRoom(trajectoryPose(8), 100, 8, 0.8));
  ASSERT_TRUE(r.pose.has_value());
  EXPECT_LT(transErr(*r.pose, shift + trajectoryPose(8)), 0.03);
  EXPECT_THROW(odo.registerKeyframes(0, 999), std::out_of_range);
}

TEST(RgbdOdometry, RoiModeFallsBackToFullImageWithoutRoi)
{
  // Low contrast: ORB finds corners but Canny (250/300) finds no edge -> no ROI.
  auto o = baseOptions();
  o.mode = EFrontEndMode::RoiBig;
  CRgbdOdometry odo(o);
  const auto res = run(odo, 25, 8);
  for (std::size_t k = 1; k < res.size(); ++k)
  {
    EXPECT_FALSE(res[k].roi.has_value());
    ASSERT_EQ(res[k].method, ETrackingMethod::FullImageFallback) << "frame " << k;
    ASSERT_TRUE(res[k].pose.has_value());
    EXPECT_LT(transErr(*res[k].pose, trajectoryPose(k)), 0.03);
  }
  EXPECT_EQ(odo.stats().noRoi, res.size());
  EXPECT_EQ(odo.stats().fullImageFallback, res.size() - 1);
  EXPECT_EQ(odo.stats().lost, 0u);
  EXPECT_TRUE(odo.keyframe(0).fullImageFallback);
}

TEST(RgbdOdometry, RoiModeUsesRoiFeaturesWhenPresent)
{
  auto o = baseOptions();
  o.mode = EFrontEndMode::RoiBig;
  CRgbdOdometry odo(o);
  const auto res = run(odo, 110, 6);
  for (std::size_t k = 1; k < res.size(); ++k)
  {
    ASSERT_TRUE(res[k].roi.has_value()) << "frame " << k;
    ASSERT_EQ(res[k].method, ETrackingMethod::RoiFeatures) << "frame " << k;
    EXPECT_LE(res[k].trackingFeatures, res[k].featuresWithDepth);
    EXPECT_EQ(res[k].trackingFeatures, res[k].roiFeatures);
    EXPECT_LT(transErr(*res[k].pose, trajectoryPose(k)), 0.03);
  }
}

TEST(RgbdOdometry, PreparedFrameCarriesStageOne)
{
  auto o = baseOptions();
  o.mode = EFrontEndMode::RoiBig;
  CRgbdOdometry odo(o);
  odo.setInitialPose(trajectoryPose(0));
  const auto f0 = renderRoom(trajectoryPose(0), 110, 0, 0.0);
  const auto f1 = renderRoom(trajectoryPose(1), 110, 1, 0.1);
  // prepare() runs stage 1 once; process() uses its ROI as given.
  const auto p0 = odo.prepare(f0);
  ASSERT_TRUE(p0.roiDetected);
  ASSERT_TRUE(p0.roi.has_value());
  EXPECT_EQ(p0.grey.type(), CV_8UC1);
  const auto r0 = odo.process(p0);
  ASSERT_TRUE(r0.roi.has_value());
  EXPECT_EQ(*r0.roi, p0.roi->box);
  auto p1 = odo.prepare(f1);
  ASSERT_TRUE(p1.roi.has_value());
  p1.roi->box = cv::Rect(10, 20, 300, 200);
  EXPECT_EQ(*odo.process(p1).roi, cv::Rect(10, 20, 300, 200));
  // The raw-frame overload prepares on the caller's thread: the same ROI.
  CRgbdOdometry other(o);
  EXPECT_EQ(*other.process(f0).roi, p0.roi->box);
  // Bad frames are refused before any work.
  auto bad = f0;
  bad.depth = cv::Mat(2, 2, CV_32FC1, cv::Scalar(1.0));
  EXPECT_THROW(odo.prepare(bad), std::invalid_argument);
}

TEST(RgbdOdometry, TraditionalModeDetectsRoiForKeyframesOnly)
{
  CRgbdOdometry odo(baseOptions());
  const auto p = odo.prepare(renderRoom(trajectoryPose(0), 110, 0, 0.0));
  EXPECT_FALSE(p.roiDetected);
  EXPECT_EQ(p.roi_ms, 0.0);
  const auto res = run(odo, 110, 6);
  for (const auto& r : res)
    EXPECT_EQ(r.roi.has_value(), r.isNewKeyframe) << "frame " << r.frameIndex;
  for (const auto& kf : odo.keyframes())
    EXPECT_TRUE(kf.roi.has_value()) << "keyframe " << kf.id;
  EXPECT_EQ(odo.stats().noRoi, 0u);
}

TEST(RgbdOdometry, FlowFramesRunStageOneOnlyWhenTheyNeedTheRoi)
{
  // Low contrast: features, no ROI. With flow_describe_roi = when_weak an
  // ordinary frame follows its reference's anchors and needs no ROI, so
  // stage 1 runs for the keyframes only (their ROI is the back end's
  // landmark), not on every frame whose reference has none to follow.
  auto o = baseOptions();
  o.mode = EFrontEndMode::RoiBig;
  o.roi_extraction = "flow";
  o.flow_describe_roi = "when_weak";
  CRgbdOdometry odo(o);
  const auto res = run(odo, 25, 10);
  std::size_t flowFrames = 0, keyframes = 0;
  for (const auto& r : res)
  {
    ASSERT_TRUE(r.pose.has_value()) << "frame " << r.frameIndex;
    EXPECT_FALSE(r.roi.has_value()) << "frame " << r.frameIndex;
    keyframes += r.isNewKeyframe ? 1 : 0;
    if (r.isNewKeyframe || r.method != ETrackingMethod::Flow)
      continue;
    ++flowFrames;
    EXPECT_EQ(r.times.roi_ms, 0.0) << "frame " << r.frameIndex;
    EXPECT_LT(transErr(*r.pose, trajectoryPose(r.frameIndex)), 0.03);
  }
  EXPECT_GE(flowFrames, 3u);
  // Counted where stage 1 ran and found none: the keyframes.
  EXPECT_EQ(odo.stats().noRoi, keyframes);
}

TEST(RgbdOdometry, StrictRoiLosesFramesWithoutRoi)
{
  auto o = baseOptions();
  o.mode = EFrontEndMode::RoiBig;
  o.strict_roi = true;
  CRgbdOdometry odo(o);
  const auto res = run(odo, 25, 5);
  for (const auto& r : res)
  {
    EXPECT_EQ(r.method, ETrackingMethod::Lost);
    EXPECT_FALSE(r.pose.has_value());
    EXPECT_FALSE(r.isNewKeyframe);
  }
  EXPECT_EQ(odo.stats().lost, res.size());
  EXPECT_TRUE(odo.keyframes().empty());
}

TEST(RgbdOdometry, FeaturelessRoomTrackedByDepthIcp)
{
  auto o = baseOptions();
  o.mode = EFrontEndMode::RoiBig;  // ROI mode must not fail either
  CRgbdOdometry odo(o);
  const auto res = run(odo, 0, 12);
  for (std::size_t k = 1; k < res.size(); ++k)
  {
    ASSERT_EQ(res[k].method, ETrackingMethod::DepthIcp) << "frame " << k;
    ASSERT_TRUE(res[k].pose.has_value());
    EXPECT_LT(transErr(*res[k].pose, trajectoryPose(k)), 0.01) << "frame " << k;
    EXPECT_LT(rotErrDeg(*res[k].pose, trajectoryPose(k)), 0.3) << "frame " << k;
    EXPECT_LT(res[k].times.icp_ms, 100.0 * roislam::testing::kTimeBoundScale);
  }
  EXPECT_EQ(odo.stats().depthIcp, res.size() - 1);
  EXPECT_GE(odo.keyframes().size(), 2u);
}

TEST(RgbdOdometry, FeaturelessWithoutIcpUsesConstantVelocity)
{
  auto o = baseOptions();
  o.icp_fallback = false;
  CRgbdOdometry odo(o);
  const auto res = run(odo, 0, 5);
  for (std::size_t k = 1; k < res.size(); ++k)
  {
    EXPECT_EQ(res[k].method, ETrackingMethod::ConstantVelocity);
    EXPECT_TRUE(res[k].pose.has_value());
  }
  // No motion was ever measured: the prediction stays at the start.
  EXPECT_LT(transErr(*res.back().pose, trajectoryPose(0)), 1e-9);
}

namespace
{
/** A pan of 7 deg a frame (the room's long walls sweep through the view):
 *  each frame still overlaps the last by 90 %, its keyframe less and less. */
CPose3D panPose(std::size_t k)
{
  const double t = static_cast<double>(k);
  return CPose3D(0.004 * t, 0.0, 0.002 * t, 0.0, 7.0 * t * M_PI / 180.0, 0.0);
}

/** For the pans: keyframes only when a frame no longer registers (no motion
 *  bound, no inlier count), and no depth ICP to fall back on. */
CRgbdOdometry::TOptions panOptions()
{
  auto o = baseOptions();
  o.icp_fallback = false;
  o.keyframe_rotation_deg = 180;
  o.keyframe_translation_m = 10;
  o.keyframe_min_inliers = 0;
  return o;
}
}  // namespace

TEST(RgbdOdometry, FrameThatLosesItsKeyframeIsBridgedThroughThePreviousOne)
{
  // Keyframes only when a frame no longer registers; no depth ICP. Without
  // the bridge such a frame falls to constant velocity; with it, it is
  // registered against the previous frame, chained to the keyframe that one
  // tracked, and becomes the next keyframe, its edge from that keyframe.
  for (const bool bridge : {false, true})
  {
    SCOPED_TRACE(bridge);
    auto o = panOptions();
    o.bridge_previous_frame = bridge;
    CRgbdOdometry odo(o);
    odo.setInitialPose(panPose(0));
    std::vector<TFrameResult> res;
    for (std::size_t k = 0; k < 14; ++k)
      res.push_back(odo.process(renderRoom(panPose(k), 100, k, 0.1 * k)));
    std::size_t bridged = 0, cv = 0;
    for (std::size_t k = 1; k < res.size(); ++k)
    {
      const auto& r = res[k];
      ASSERT_TRUE(r.pose.has_value()) << "frame " << k;
      cv += r.method == ETrackingMethod::ConstantVelocity ? 1 : 0;
      if (!r.bridged)
        continue;
      ++bridged;
      EXPECT_EQ(r.method, ETrackingMethod::Features) << "frame " << k;
      EXPECT_TRUE(r.isNewKeyframe) << "frame " << k;
      // From the keyframe the previous frame tracked, as a feature edge.
      ASSERT_FALSE(r.constraints.empty());
      EXPECT_EQ(r.constraints.front().fromKeyframe, res[k - 1].referenceKeyframe);
      EXPECT_EQ(r.constraints.front().method, ETrackingMethod::Features);
      EXPECT_GT(r.constraints.front().information(0, 0), 0);
      EXPECT_LT(transErr(*r.pose, panPose(k)), 0.01) << "frame " << k;
      EXPECT_LT(rotErrDeg(*r.pose, panPose(k)), 0.3) << "frame " << k;
      // Its information is less than the previous frame's registration's:
      // the two registrations' covariances add up.
      EXPECT_LT(r.relativeInformation(0, 0), res[k - 1].relativeInformation(0, 0) * 1.0001);
    }
    EXPECT_EQ(odo.stats().bridged, bridged);
    std::printf(
        "bridge %d: %zu bridged, %zu constant-velocity frames, %zu keyframes; last frame %.1f mm "
        "off\n",
        bridge ? 1 : 0, bridged, cv, odo.keyframes().size(),
        1e3 * transErr(*res.back().pose, panPose(res.size() - 1)));
    if (bridge)
    {
      EXPECT_GE(bridged, 1u);
      EXPECT_EQ(cv, 0u);
      EXPECT_LT(transErr(*res.back().pose, panPose(res.size() - 1)), 0.02);
    }
    else
    {
      EXPECT_EQ(bridged, 0u);
      EXPECT_GE(cv, 1u);
    }
  }
}

TEST(RgbdOdometry, BridgeAndDepthIcpTogether)
{
  // The pan above with depth ICP available too. Where a frame loses its
  // keyframe, the chain through the previous frame and depth ICP against
  // the last keyframe compete (IcpConsistency.h icpBetterDetermined, tested
  // there): either way the frame is tracked, not left to constant
  // velocity, and every frame stays within about a centimetre.
  auto o = panOptions();
  o.bridge_previous_frame = true;
  o.icp_fallback = true;
  CRgbdOdometry odo(o);
  odo.setInitialPose(panPose(0));
  std::size_t bridged = 0, icp = 0;
  for (std::size_t k = 0; k < 14; ++k)
  {
    const auto r = odo.process(renderRoom(panPose(k), 100, k, 0.1 * k));
    ASSERT_TRUE(r.pose.has_value()) << "frame " << k;
    EXPECT_NE(r.method, ETrackingMethod::ConstantVelocity) << "frame " << k;
    EXPECT_LT(transErr(*r.pose, panPose(k)), 0.012) << "frame " << k;
    bridged += r.bridged ? 1 : 0;
    icp += r.method == ETrackingMethod::DepthIcp ? 1 : 0;
  }
  std::printf("bridged %zu, depth ICP %zu\n", bridged, icp);
  EXPECT_GE(bridged + icp, 1u);
}

TEST(RgbdOdometry, KeyframeBeforeTheRegistrationsWearOut)
{
  // The pan of the test above, neither bridge nor depth ICP: with
  // keyframe_min_inlier_share a keyframe is made while the frame still keeps
  // half the inliers its keyframe gave, so no frame loses its keyframe.
  for (const double share : {0.0, 0.5})
  {
    SCOPED_TRACE(share);
    auto o = panOptions();
    o.keyframe_min_inlier_share = share;
    CRgbdOdometry odo(o);
    odo.setInitialPose(panPose(0));
    std::map<std::size_t, std::size_t> best;
    std::size_t cv = 0;
    for (std::size_t k = 0; k < 14; ++k)
    {
      const auto r = odo.process(renderRoom(panPose(k), 100, k, 0.1 * k));
      ASSERT_TRUE(r.pose.has_value());
      cv += r.method == ETrackingMethod::ConstantVelocity ? 1 : 0;
      if (k == 0 || r.method != ETrackingMethod::Features)
        continue;
      if (share > 0 && !r.isNewKeyframe && best.count(r.referenceKeyframe))
      {
        EXPECT_GE(static_cast<double>(r.inliers), share * best[r.referenceKeyframe])
            << "frame " << k;
      }
      if (share > 0)
      {
        EXPECT_LT(transErr(*r.pose, panPose(k)), 0.025) << "frame " << k;
      }
      if (!r.isNewKeyframe)
        best[r.referenceKeyframe] = std::max(best[r.referenceKeyframe], r.inliers);
    }
    std::printf(
        "share %.1f: %zu keyframes, %zu constant-velocity frames\n", share, odo.keyframes().size(),
        cv);
    if (share > 0)
    {
      EXPECT_EQ(cv, 0u);
      EXPECT_GE(odo.keyframes().size(), 2u);
    }
    else
      EXPECT_GE(cv, 1u);
  }
}

TEST(RgbdOdometry, KeyframeLeftBehindKeepsAnEdgeChainedThroughThePreviousFrame)
{
  // The pan of the test above to 105 deg, then back 14 deg a frame: the
  // frame back at 49 deg no longer registers against the keyframe the pan
  // made last but does against an older one, its reference. Its edge from
  // the last one is chained through the previous frame, which tracked it
  // (without the bridge that keyframe keeps one edge).
  const std::vector<double> anglesDeg = {0,  7,  14, 21, 28,  35, 42, 49, 56, 63, 70,
                                         77, 84, 91, 98, 105, 91, 77, 63, 49, 35};
  auto pose = [&](std::size_t k)
  {
    const double t = static_cast<double>(k);
    return CPose3D(0.004 * t, 0.0, 0.002 * t, 0.0, anglesDeg[k] * M_PI / 180.0, 0.0);
  };
  for (const bool bridge : {false, true})
  {
    SCOPED_TRACE(bridge);
    auto o = panOptions();
    o.bridge_previous_frame = bridge;
    CRgbdOdometry odo(o);
    odo.setInitialPose(pose(0));
    std::vector<TFrameResult> res;
    std::vector<std::size_t> keyframeFrame = {0};
    std::size_t chained = 0;
    for (std::size_t k = 0; k < anglesDeg.size(); ++k)
    {
      res.push_back(odo.process(renderRoom(pose(k), 100, k, 0.1 * k)));
      const auto& r = res.back();
      if (!r.isNewKeyframe || k == 0)
        continue;
      keyframeFrame.push_back(k);
      for (std::size_t c = 0; c < r.constraints.size(); ++c)
      {
        const auto& e = r.constraints[c];
        const CPose3D truth = pose(k) - pose(keyframeFrame.at(e.fromKeyframe));
        // Chained edges come after the first, from the previous frame's reference.
        if (c == 0 || r.bridged || e.fromKeyframe != res[k - 1].referenceKeyframe ||
            e.fromKeyframe == r.referenceKeyframe)
          continue;
        ++chained;
        EXPECT_EQ(e.method, ETrackingMethod::Features);
        EXPECT_LT(transErr(e.relativePose, truth), 0.015) << "frame " << k;
        EXPECT_LT(rotErrDeg(e.relativePose, truth), 0.5) << "frame " << k;
      }
    }
    std::printf(
        "bridge %d: %zu keyframes, %zu frames and %zu keyframe edges chained\n", bridge ? 1 : 0,
        odo.keyframes().size(), odo.stats().bridged, odo.stats().bridgedConstraints);
    EXPECT_EQ(odo.stats().bridgedConstraints, chained);
    if (bridge)
      EXPECT_GE(chained, 1u);
    else
      EXPECT_EQ(odo.stats().bridged + chained, 0u);
  }
}

namespace
{
/** The room seen by a camera of twice the resolution (1280 x 960): the
 *  640 x 480 render upscaled, the intrinsics with it (pixel centres). */
roislam::io::TRGBDFrame doubled(const roislam::io::TRGBDFrame& f)
{
  roislam::io::TRGBDFrame g = f;
  cv::resize(f.rgb, g.rgb, cv::Size(), 2, 2, cv::INTER_LINEAR);
  cv::resize(f.depth, g.depth, cv::Size(), 2, 2, cv::INTER_NEAREST);
  g.camera.ncols = 1280;
  g.camera.nrows = 960;
  g.camera.setIntrinsicParamsFromValues(
      2 * f.camera.fx(), 2 * f.camera.fy(), 2 * f.camera.cx() + 0.5, 2 * f.camera.cy() + 0.5);
  return g;
}
}  // namespace

TEST(RgbdOdometry, CamerasWiderThan1280PxDescribeAtHalfResolutionWhenAsked)
{
  // feature_resolution = auto describes the whole image at 640 x 480 (a
  // quarter of the pixels), its keypoints in the camera's pixels; full at
  // the camera's own. Both track the room.
  for (const std::string res : {"full", "auto"})
  {
    auto o = baseOptions();
    o.feature_resolution = res;
    CRgbdOdometry odo(o);
    odo.setInitialPose(trajectoryPose(0));
    for (std::size_t k = 0; k < 6; ++k)
    {
      const auto r = odo.process(doubled(renderRoom(trajectoryPose(k), 100, k, 0.1 * k)));
      const std::size_t pixels = res == "auto" ? 640u * 480u : 1280u * 960u;
      EXPECT_EQ(r.work.extensionPixels, pixels) << res << " frame " << k;
      ASSERT_TRUE(r.pose.has_value());
      if (k == 0)
        continue;
      EXPECT_EQ(r.method, ETrackingMethod::Features) << res << " frame " << k;
      EXPECT_LT(transErr(*r.pose, trajectoryPose(k)), 0.02) << res << " frame " << k;
      EXPECT_LT(rotErrDeg(*r.pose, trajectoryPose(k)), 0.5) << res << " frame " << k;
    }
    const auto& px = odo.lastFeaturePixels();
    ASSERT_GT(px.size(), 100u);
    float right = 0, bottom = 0;
    for (const auto& u : px)
    {
      EXPECT_TRUE(u.x >= 0 && u.x < 1280 && u.y >= 0 && u.y < 960) << u;
      right = std::max(right, u.x);
      bottom = std::max(bottom, u.y);
    }
    // In the camera's pixels, not the working image's.
    EXPECT_GT(right, 1000.f) << res;
    EXPECT_GT(bottom, 700.f) << res;
  }
}

TEST(RgbdOdometry, CamerasWiderThan1280PxSampleDepthAsSparselyAsVga)
{
  // ICP's grid keeps a 640 x 480 camera's density: at 1280 x 960 every 8th
  // pixel (160 x 120 cells), not every 4th (320 x 240).
  CRgbdOdometry odo(baseOptions());
  odo.setInitialPose(trajectoryPose(0));
  for (std::size_t k = 0; k < 4; ++k)
  {
    const auto r = odo.process(doubled(renderRoom(trajectoryPose(k), 0, k, 0.1 * k)));
    if (k == 0)
      continue;
    ASSERT_EQ(r.method, ETrackingMethod::DepthIcp) << "frame " << k;
    EXPECT_LE(r.inliers, 160u * 120u) << "frame " << k;
    EXPECT_GT(r.inliers, 160u * 120u / 2) << "frame " << k;
    EXPECT_LT(transErr(*r.pose, trajectoryPose(k)), 0.01) << "frame " << k;
    EXPECT_LT(rotErrDeg(*r.pose, trajectoryPose(k)), 0.3) << "frame " << k;
  }
}

TEST(RgbdOdometry, OptionsIniRoundTripAndErrors)
{
  auto o = baseOptions();
  o.mode = EFrontEndMode::RoiSmall;
  o.keyframe_translation_m = 0.2;
  o.recent_keyframes = 1;
  o.min_roi_inliers = 35;
  o.max_roi_sigma_m = 0.004;
  o.max_roi_sigma_deg = 0.3;
  o.icp_refine_sigma_m = 0.02;
  o.icp_fusion = "weak";
  o.icp_min_share = 0.25;
  o.icp_colour_check = false;
  o.icp_probe_interval = 7;
  o.icp_converged_step_sigma = 0.25;
  o.feature_resolution = "auto";
  o.flow_anchors = "corners";
  o.rolling_shutter_ms = 25;
  o.keyframe_full_features = false;
  o.keyframe_full_registration = false;
  o.bridge_previous_frame = true;
  o.keyframe_min_inlier_share = 0.4;
  o.keyframe_on_weak_roi = true;
  mrpt::config::CConfigFileMemory cfg;
  o.saveToConfigFile(cfg, "FrontEnd");
  CRgbdOdometry::TOptions l;
  l.loadFromConfigFile(cfg, "FrontEnd");
  EXPECT_EQ(l.mode, EFrontEndMode::RoiSmall);
  EXPECT_DOUBLE_EQ(l.keyframe_translation_m, 0.2);
  EXPECT_EQ(l.recent_keyframes, 1);
  EXPECT_EQ(l.min_roi_inliers, 35);
  EXPECT_DOUBLE_EQ(l.max_roi_sigma_m, 0.004);
  EXPECT_DOUBLE_EQ(l.max_roi_sigma_deg, 0.3);
  EXPECT_DOUBLE_EQ(l.icp_refine_sigma_m, 0.02);
  EXPECT_EQ(l.icp_fusion, "weak");
  EXPECT_DOUBLE_EQ(l.icp_min_share, 0.25);
  EXPECT_FALSE(l.icp_colour_check);
  EXPECT_EQ(l.icp_probe_interval, 7);
  EXPECT_DOUBLE_EQ(l.icp_converged_step_sigma, 0.25);
  EXPECT_EQ(l.feature_resolution, "auto");
  EXPECT_EQ(l.flow_anchors, "corners");
  EXPECT_DOUBLE_EQ(l.rolling_shutter_ms, 25);
  EXPECT_TRUE(l.bridge_previous_frame);
  EXPECT_DOUBLE_EQ(l.keyframe_min_inlier_share, 0.4);
  EXPECT_TRUE(l.keyframe_on_weak_roi);
  EXPECT_FALSE(l.keyframe_full_features);
  EXPECT_FALSE(l.keyframe_full_registration);
  EXPECT_EQ(l.extractor.max_features, 500);

  for (const auto& [key, value] : std::vector<std::pair<std::string, std::string>>{
           {"mode", "roi_huge"},
           {"icp_fusion", "sometimes"},
           {"feature_resolution", "half"},
           {"flow_anchors", "edges"}})
  {
    mrpt::config::CConfigFileMemory bad;
    bad.write("FrontEnd", key, value);
    try
    {
      CRgbdOdometry::TOptions b;
      b.loadFromConfigFile(bad, "FrontEnd");
      FAIL() << "expected an exception for " << key;
    }
    catch (const std::invalid_argument& e)
    {
      EXPECT_NE(std::string(e.what()).find("[FrontEnd] " + key), std::string::npos);
    }
  }
  mrpt::config::CConfigFileMemory bad2;
  bad2.write("FrontEnd", "ransac_threshold_m", -1.0);
  CRgbdOdometry::TOptions b2;
  EXPECT_THROW(b2.loadFromConfigFile(bad2, "FrontEnd"), std::invalid_argument);
  for (const auto& [key, value] : std::vector<std::pair<std::string, double>>{
           {"max_roi_sigma_m", -0.1},
           {"max_roi_sigma_deg", -0.1},
           {"icp_refine_sigma_m", -0.1},
           {"icp_min_share", -0.5},
           {"icp_probe_interval", 0},
           {"icp_converged_step_sigma", -0.1},
           {"rolling_shutter_ms", -1001},
           {"rolling_shutter_ms", 2000},
           {"pixel_sigma_px", -0.5},
           {"keyframe_min_inlier_share", -0.1},
           {"keyframe_min_inlier_share", 1.0},
           {"reprojection_threshold_px", 0}})
  {
    mrpt::config::CConfigFileMemory bad3;
    bad3.write("FrontEnd", key, value);
    try
    {
      CRgbdOdometry::TOptions b3;
      b3.loadFromConfigFile(bad3, "FrontEnd");
      FAIL() << "expected an exception for " << key;
    }
    catch (const std::invalid_argument& e)
    {
      EXPECT_NE(std::string(e.what()).find("[FrontEnd] " + key), std::string::npos) << e.what();
    }
  }

  CRgbdOdometry odo;
  roislam::io::TRGBDFrame empty;
  EXPECT_THROW(odo.process(empty), std::invalid_argument);
  EXPECT_EQ(toString(ETrackingMethod::DepthIcp), "depth_icp");
  EXPECT_EQ(frontEndModeFromString("roi_big"), EFrontEndMode::RoiBig);
}
