/* Private: the state of CRgbdOdometry between frames (TImpl) and the data
 * one frame carries from stage to stage inside process() (TFrameWork). Every
 * stage reads what the stages before it wrote into TFrameWork and adds its
 * own results; nothing flows backwards.
 */
#pragma once

#include <roislam/features/CFeatureExtractor.h>
#include <roislam/frontend/CRgbdOdometry.h>
#include <roislam/matching/CFeatureMatcher.h>
#include <roislam/matching/CRigidTransformRansac.h>
#include <roislam/roi/CRoiDetector.h>

#include <map>
#include <memory>
#include <optional>
#include <set>
#include <vector>

#include "CDepthIcp.h"
#include "DepthTimeOffset.h"
#include "FeatureLifting.h"
#include "FlowTracking.h"
#include "IcpConsistency.h"
#include "KeyframeOverlap.h"
#include "KeyframeRegistration.h"
#include "PhotometricCheck.h"
#include "RollingShutter.h"
#include "Timing.h"
#include "WorkingResolution.h"

namespace roislam::frontend
{
namespace detail
{
/** Depth ICP as fused into a registration: its estimate and the scale its
 *  information was divided by (icp_fusion = measured; 1 otherwise). */
struct TFusedIcp
{
  CDepthIcp::TResult icp;
  double scale = 1;
};
}  // namespace detail

struct CRgbdOdometry::TImpl
{
  roi::CRoiDetector roiDetector;
  features::CFeatureExtractor extractor;
  matching::CFeatureMatcher matcher;
  matching::CRigidTransformRansac ransac;

  // Camera-dependent state, rebuilt when the intrinsics change.
  bool haveCamera = false;
  mrpt::img::TCamera camera;
  cv::Mat K, dist;
  detail::TPinhole pinhole;
  std::unique_ptr<detail::CDepthIcp> icp;
  /** ICP maps of the most recent keyframes only (memory). */
  std::map<std::size_t, detail::CDepthIcp::TMap> icpMaps;
  /** icp_fusion = measured: the same keyframes' grey and depth images, and
   *  their photometric samples once one was needed (PhotometricCheck.h:
   *  the arbiter where features and ICP disagree; most keyframes never
   *  need one, and sampling costs about 5 ms). */
  struct TPhotoKeyframe
  {
    cv::Mat grey, depth;
    std::optional<detail::TPhotoSamples> samples;
  };
  std::map<std::size_t, TPhotoKeyframe> photoKeyframes;
  /** roi_extraction = flow: the optical-flow pyramids of the most recent
   *  keyframes' images (as icpMaps). */
  std::map<std::size_t, detail::TFlowPyramid> flowPyramids;
  detail::TFlowParams flowParams;

  // Tracking state: the last tracked (non-lost) frame relative to a keyframe.
  bool haveLast = false;
  std::size_t lastRef = 0;
  mrpt::poses::CPose3D lastRel;
  /** Motion between the last two tracked frames: P_k = P_{k-1} (+) velocity. */
  mrpt::poses::CPose3D velocity;
  /** Colour stamp of the last tracked frame; the interval velocity spans
   *  (0 = unknown). */
  double lastStamp = 0, velocityDt = 0;
  bool haveStamp = false;
  /** The first keyframe is made before any velocity is known: its raw
   *  points wait here until the next frame measures one (rolling shutter). */
  std::optional<detail::TUncorrectedKeyframe> uncorrected;
  /** depth_time_correction: the depth images' offset from the colour ones. */
  detail::CDepthTimeOffset depthTime;
  /** icp_fusion = measured: how far ICP agrees with the features. Trusted
   *  down to every pair independent (IcpConsistency.h). */
  detail::CIcpConsistency icpConsistency{30, 10, detail::CDepthIcp::kIndependentPairShare};
  /** Registrations since depth ICP last ran (icp_probe_interval). */
  std::size_t framesSinceIcp = 0;
  /** roi_extraction = region: the tracking region's minimum area, as a
   *  multiple of roi_min_area_fraction. It grows after each region
   *  registration that failed or left the pose poorly determined, and
   *  shrinks back after each good one, so that the region is as large as
   *  this scene needs for a determined pose (StageTrack.cpp). */
  double regionGrowth = 1;
  /** keyframe_min_inlier_share: the most feature inliers a frame had
   *  against each recent keyframe (erased with their ICP maps). */
  std::map<std::size_t, std::size_t> bestInliers;
  /** keyframe_min_inliers: the recent keyframes against which a frame's
   *  described features or its anchors registered with at least that many
   *  inliers, and the map's first: below the floor, only these wear out
   *  (StageKeyframe.cpp). */
  std::set<std::size_t> atInlierFloor;
  /** bridge_previous_frame (not in strict_roi): the last frame, if it was
   *  tracked by its described features and did not become a keyframe
   *  (StageBridge.cpp). Unset, nothing is bridged. */
  std::optional<detail::TTrackedFrame> previous;
  /** Pixels of the features the last process() call described
   *  (lastFeaturePixels()). */
  std::vector<cv::Point2f> lastFeaturePixels;

  explicit TImpl(const TOptions& o);
  /** Rebuilds the camera-dependent state when the intrinsics change. */
  void useCamera(const mrpt::img::TCamera& camera, const TOptions& o);
  /** The motion since the last tracked frame, seen at `stamp`. */
  void setVelocity(const mrpt::poses::CPose3D& motion, double stamp)
  {
    velocity = motion;
    velocityDt = haveStamp ? stamp - lastStamp : 0;
  }
  /** The camera and depth range views are compared in (KeyframeOverlap.h). */
  detail::TViewModel view(const cv::Size& image, const TOptions& o) const
  {
    return {pinhole, image, o.min_depth_m, o.max_depth_m};
  }
  /** A frame's features lifted at the colour image's time (the depth rule,
   *  depth-time alignment) and corrected for the rolling shutter, both
   *  with `rate`: every set a frame describes or follows is lifted so. */
  detail::TLiftedFeatures lift(
      const features::TFeatureSet& set, const cv::Mat& depth, double depthDt,
      const detail::TCameraRate& rate, const TOptions& o) const
  {
    detail::TLiftedFeatures l =
        detail::liftAtColourTime(set, depth, K, dist, pinhole, o, rate, depthDt);
    detail::rectifyRollingShutter(l, rate, o.rolling_shutter_ms * 1e-3, pinhole);
    return l;
  }
  /** registerSets() with this odometry's matcher, RANSAC and camera. */
  std::optional<detail::TRegistration> registerSets(
      const TKeyframe& ref, const TKeyframe& cur, const TOptions& o,
      std::size_t* matchesOut = nullptr, TStageTimes* times = nullptr,
      const detail::TKnownPairs* known = nullptr) const;
  /** query registered against the previous frame and chained to the
   *  keyframe that frame tracked (previous->ref); nullopt without a previous
   *  frame or a registration (StageBridge.cpp). */
  std::optional<detail::TRegistration> chainedThroughPrevious(
      const TKeyframe& query, const TOptions& o, std::size_t* matchesOut = nullptr,
      TStageTimes* times = nullptr) const;
};

/** One frame on its way through the stages of process(). */
struct CRgbdOdometry::TFrameWork
{
  explicit TFrameWork(const TPreparedFrame& f) : in(f) {}

  const TPreparedFrame& in;
  detail::Clock::time_point start = detail::Clock::now();
  /** What process() returns, filled stage by stage. */
  TFrameResult res;

  // extractFeatures
  /** The grey image at the features' working resolution (in.featureGrey,
   *  or made here for a frame prepared without it). */
  detail::TWorkingImage featureImage;
  /** Every feature described so far: the tracking region's first, then the
   *  extension's (extendToImage). */
  features::TFeatureSet all;
  /** Stage 2 ran on the region only so far (ROI-only, may be extended). */
  bool regionOnly = false;
  /** Flow mode with the reference keyframe's anchors at hand: the frame
   *  describes its ROI only and follows the rest (decided once, here). */
  bool flowFrame = false;
  /** flow_describe_roi = when_weak: the flow frame has a ROI it has not
   *  described; describeRoi() does when the anchors do not determine the
   *  pose. */
  bool roiDeferred = false;
  // liftFeatures
  detail::TLiftedFeatures lifted;
  /** Features tracked with (indices into all, a subset of lifted.valid):
   *  the ROI's in ROI modes, else every valid one. */
  std::vector<int> chosen;
  /** The whole image's set (keyframe storage, fallback) and the tracked one. */
  TKeyframe full, cur;
  /** ROI mode tracked with the whole image's features. */
  bool fallback = false;
  /** Flow: the ROI had too few features (or there was none), so the pose
   *  comes from the anchors followed everywhere (ETrackingMethod::Flow). */
  bool flowFallback = false;
  /** strict_roi: too few ROI features, the frame will be Lost. */
  bool strictLost = false;
  /** The rolling-shutter correction's first guess (the last motion), and
   *  the one lifted's points carry now (the measured one after
   *  refineRollingShutter). */
  detail::TCameraRate ratePredicted, rateApplied;
  /** Depth image's time minus the colour image's, s (depth_time_correction;
   *  0 = none or unknown). */
  double depthDt = 0;
  /** Stage 1 ran on this frame (in prepare(), or later where needed). */
  bool roiDetected = false;

  // predictMotion
  std::size_t lastKf = 0;
  /** World pose of the last tracked frame, the predicted one (constant
   *  velocity), and the prediction relative to the last keyframe. */
  mrpt::poses::CPose3D lastWorld, predictedWorld, predictedRel;
  /** keyframe_policy = overlap: the keyframes to track against, best
   *  overlapping the predicted view first (empty: the recent ones). */
  std::vector<std::size_t> candidates;
  /** keyframe_place_limit: the predicted pose's place has its keyframes,
   *  the candidates are they, nearest first, and the frame adds none while
   *  it stays within the motion bounds of its reference. */
  bool placeFull = false;
  /** keyframe_prediction: at the predicted pose the frame would become a
   *  keyframe, so it describes the whole image at once and tracks with it
   *  (decided before stage 2). */
  bool keyframeExpected = false;

  // trackFeatures (roi_extraction = flow): the reference keyframe's
  // features followed into the frame outside its region. w.cur is then the
  // region's set followed by theirs (regionSet alone is what other
  // keyframes are matched with), and `known` their correspondences.
  std::optional<std::size_t> flowRef;
  detail::TFlowTracks flow;
  detail::TLiftedFeatures flowLifted;
  TKeyframe regionSet;
  detail::TKnownPairs known;
  /** rescueWithAnchors: the whole image's features and the anchors tracked
   *  the frame together (w.cur holds both; no keyframe edge needs to
   *  register the whole image again). */
  bool anchorsJoinedFull = false;
  /** The flow reference as registrations against its anchors see it
   *  (detail::withAnchors). */
  TKeyframe flowRefView;
  /** The frame's ICP map, built once: depth refinement, the depth-only
   *  fallback and a new keyframe's storage share it. */
  std::optional<detail::CDepthIcp::TMap> icpMap;
  const detail::CDepthIcp::TMap& currentIcpMap(const detail::CDepthIcp& icp)
  {
    if (!icpMap)
      icpMap = icp.buildMap(in.frame.depth);
    return *icpMap;
  }
  /** The keyframe registrations against reference `id` use. */
  const TKeyframe& reference(const std::deque<TKeyframe>& keyframes, std::size_t id) const
  {
    return flowRef && *flowRef == id ? flowRefView : keyframes[id];
  }

  // trackFeatures, refine*
  std::optional<detail::TRegistration> reg;
  /** Keyframe the registration is against. */
  std::size_t ref = 0;
  /** reg is chained through the previous frame (bridgeFromPrevious): the
   *  frame becomes a keyframe. */
  bool bridged = false;
  /** refineWithDepth's depth ICP against `ref`, started from reg. */
  std::optional<detail::CDepthIcp::TResult> refineIcp;
  /** refineWithDepth fused depth ICP against `ref` into reg. A keyframe
   *  registered again with the whole image's features
   *  (makeKeyframeConstraints) is fused with the same ICP: the depth
   *  constrains it no less. */
  std::optional<detail::TFusedIcp> fusedIcp;
};

namespace detail
{
/** reg fused with depth ICP, its information divided by f.scale (StageRefine.cpp). */
void fuseDepthIcp(TRegistration& reg, const TFusedIcp& f);
/** Whether depth ICP joins a registration by refineWithDepth's rule: always
 *  where it leaves the pose poorly determined (icp_refine_sigma_m), else
 *  under measured fusion where the two agree within what the scale explains
 *  (IcpConsistency.h's gate). */
bool depthIcpJoins(const TRegistration& reg, const TFusedIcp& f, const CRgbdOdometry::TOptions& o);
/** Depth ICP's share of a fused registration's information (the fused reg
 *  and what was fused into it, StageRefine.cpp): tr(Hicp / scale * H^-1) / 6,
 *  in [0, 1] (the mean share per axis where both are diagonal; free of
 *  units, as metres and radians scale both alike); 0 when reg is
 *  singular. */
double depthIcpShare(const TRegistration& reg, const TFusedIcp& f);
}  // namespace detail

bool isFeatureMethod(ETrackingMethod m);
/** s * identity. */
TInformation66 scaledIdentity(double s);
}  // namespace roislam::frontend
