/* The SLAM front end: frame-to-keyframe RGB-D visual odometry.
 *
 * Per frame, in stages (README "One frame's path"): prepare() checks the
 * frame, converts it to grey and, in ROI modes, detects the ROI (stage 1; it
 * may run on another thread, ahead); process() extracts features
 * (CFeatureExtractor): once on the whole image in traditional mode and with
 * roi_extraction = image (the ROI selecting its subset); with region or flow
 * (the shipped ROI configs) an ordinary ROI frame describes only its tracking
 * region, or follows the keyframe's anchors by optical flow, and extends to
 * the whole image at most once, when it needs to (TFrameResult's described
 * work and extension reason); lifts keypoints to 3-D with the registered
 * depth image (undistorted, invalid depth skipped, corrected for the rolling
 * shutter); matches them (CFeatureMatcher) against the last keyframe (then,
 * if that fails, up to recent_keyframes older ones); registers them by 3-D
 * RANSAC (CRigidTransformRansac) and a Gauss-Newton refinement of the
 * symmetric reprojection error over the inliers, whose Hessian gives the
 * information matrix. When features fail: depth-only projective
 * point-to-plane ICP against the reference keyframe, then constant velocity,
 * so tracking never stops (except strict_roi, see below). A new keyframe is
 * made when the motion since the last keyframe exceeds the thresholds, the
 * feature inliers drop, or the frame could only be registered against an
 * older keyframe; it brings constraints to the recent keyframes for the pose
 * graph (keyframe id == its position in keyframes(), so the back end can use
 * it as node id) and its ROI (in traditional mode detected for keyframes
 * only), the back end's landmark. The back end's optimised poses come back
 * through correctKeyframePoses().
 *
 * Called by the graph-SLAM back end (roislam::graphslam) and apps, one frame
 * at a time, in order. Not thread-safe, except prepare().
 *
 * strict_roi (ROI modes only) reproduces the dissertation: no full-image
 * fallback, no depth ICP and no constant velocity. A frame whose ROI has fewer
 * than min_roi_features features (or none), or whose ROI features do not
 * register against any recent keyframe, is Lost: TFrameResult::pose is
 * nullopt, no keyframe is made, stats().lost is incremented and the next frame
 * is again tracked against the last keyframe (so tracking resumes if the ROI
 * comes back). If the very first frames are Lost, the first frame with enough
 * ROI features becomes keyframe 0 at the initial pose. Apps should report a
 * run with lost frames as failed (the dissertation's "no trajectory"): see
 * TStats::lost. Outside strict_roi, no frame is Lost.
 *
 * In non-strict ROI modes, when the ROI features do not register, the
 * whole-image features are tried before depth ICP (FullImageFallback).
 *
 * The ini section [FrontEnd] (TOptions) and its keys: TRgbdOdometryOptions.h.
 */
#pragma once

#include <mrpt/poses/CPose3D.h>
#include <mrpt/system/COutputLogger.h>
#include <roislam/frontend/TFrameResult.h>
#include <roislam/frontend/TKeyframe.h>
#include <roislam/frontend/TPreparedFrame.h>
#include <roislam/frontend/TRgbdOdometryOptions.h>
#include <roislam/io/TRGBDFrame.h>

#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <vector>

namespace roislam::geometry
{
struct TRigid;
}

namespace roislam::frontend
{
class CRgbdOdometry : public mrpt::system::COutputLogger
{
 public:
  using TOptions = TRgbdOdometryOptions;

  /** Counters over the run. */
  struct TStats
  {
    std::size_t frames = 0;
    std::size_t initial = 0, features = 0, roiFeatures = 0, flow = 0, fullImageFallback = 0,
                depthIcp = 0, constantVelocity = 0, lost = 0;
    std::size_t keyframes = 0;
    /** Frames of a ROI mode in which stage 1 ran and found no ROI (flow
     *  with flow_describe_roi = when_weak: an ordinary frame runs it only
     *  when its reference's ROI left the view and its anchors need it). */
    std::size_t noRoi = 0;
    /** Feature-tracked frames also combined with depth ICP (icp_refine_sigma_m). */
    std::size_t icpRefined = 0;
    /** Of those, frames where the colour image sided with depth ICP against
     *  the features, and ICP's estimate replaced theirs (icp_fusion =
     *  measured; TFrameResult::icpOverruledFeatures). */
    std::size_t icpOverruledFeatures = 0;
    /** Frames where depth ICP's estimate replaced the features': those, and
     *  those where the two disagreed beyond ICP's scaled model and ICP was
     *  the better determined (TFrameResult::icpReplacedFeatures). */
    std::size_t icpReplacedFeatures = 0;
    /** The last joint fit of the features' and ICP's covariance scales
     *  (TFrameResult::featureScale, ::icpJointScale); none before one. */
    std::optional<double> featureScale, icpJointScale;
    /** Frames tracked through the previous frame, and keyframe constraints
     *  chained through it (bridge_previous_frame). */
    std::size_t bridged = 0, bridgedConstraints = 0;
    /** Frames by what stage 2 described (TDescribedWork::extension). */
    std::map<EExtension, std::size_t> extensions;
    /** Sum over frames of the described-pixel fraction. */
    double describedFractionSum = 0;
  };

  CRgbdOdometry();
  /** Throws std::invalid_argument on invalid options. */
  explicit CRgbdOdometry(const TOptions& options);
  ~CRgbdOdometry() override;

  /** World pose given to the first processed frame (default identity: world =
   *  first camera frame). Call before the first process() (or after reset()). */
  void setInitialPose(const mrpt::poses::CPose3D& pose) { m_initialPose = pose; }

  /** Stage 1 and the checks, for a frame that process() will receive later:
   *  throws std::invalid_argument unless rgb is CV_8UC3 and depth CV_32FC1
   *  of the same size as rgb and the camera; converts to grey and, in ROI
   *  modes, detects the ROI. Const and safe to call from another thread
   *  while process() runs (CSlamPipeline calls it on the thread that decodes
   *  the next frame). */
  TPreparedFrame prepare(const io::TRGBDFrame& frame) const;

  /** Tracks one prepared frame (frames in time order). The stages, in
   *  order (each in its own file, see the README's stage map):
   *  extract features -> lift them to 3-D -> track against the recent
   *  keyframes -> refine (rolling shutter, depth ICP) -> pose (or the
   *  depth-only / constant-velocity fallbacks) -> keyframe decision ->
   *  new keyframe with its constraints. */
  TFrameResult process(const TPreparedFrame& frame);
  /** prepare() then process(), on this thread. */
  TFrameResult process(const io::TRGBDFrame& frame) { return process(prepare(frame)); }

  /** All keyframes so far; keyframes()[id].id == id. References are
   *  invalidated by process() (the container may grow). */
  const std::deque<TKeyframe>& keyframes() const { return m_keyframes; }
  /** Throws std::out_of_range on a bad id. */
  const TKeyframe& keyframe(std::size_t id) const;

  /** Registers keyframe B against keyframe A from their stored features
   *  (matching + 3-D RANSAC + refinement): pose(B) = pose(A) (+) result.pose.
   *  nullopt when too few inliers. A const query, for loop-closure
   *  verification by the back end. Throws std::out_of_range on a bad id. */
  std::optional<TRelativePoseEstimate> registerKeyframes(std::size_t idA, std::size_t idB) const;

  /** The back end's correction, the one way its results reach the front end:
   *  optimised world poses of keyframes (by id; ids the front end does not
   *  have are ignored). Tracking continues from them (later frames are
   *  composed onto the corrected reference keyframe). */
  void correctKeyframePoses(const std::map<std::size_t, mrpt::poses::CPose3D>& poses);

  /** Forgets all keyframes and state (initial pose kept). */
  void reset();

  const TStats& stats() const { return m_stats; }
  /** Pixels (distorted, as detected) of every feature the last process()
   *  call described: the tracking region's first, then the extension's
   *  (TFrameResult::work). For viewers (the live view draws them); replaced
   *  by each call. */
  const std::vector<cv::Point2f>& lastFeaturePixels() const;
  const TOptions& options() const { return m_options; }

 private:
  struct TImpl;
  struct TFrameWork;
  // The stages of process(), in order (files StageExtract.cpp, StageTrack.cpp,
  // StageRefine.cpp, StageBridge.cpp, StageKeyframe.cpp).
  void extractFeatures(TFrameWork& w) const;
  void liftFeatures(TFrameWork& w) const;
  /** ROI-only frames: describes the rest of the image too (once; nothing
   *  already described again), lifts it and rebuilds the whole-image set. */
  void extendToImage(TFrameWork& w, EExtension reason) const;
  /** flow_describe_roi = when_weak: describes the frame's ROI (once), lifts
   *  it and makes w.cur its features plus the followed anchors; false when
   *  there is nothing to describe. */
  bool describeRoi(TFrameWork& w) const;
  /** The feature set of w's lifted features `idx`, stamped with the frame. */
  TKeyframe frameSet(const TFrameWork& w, const std::vector<int>& idx) const;
  /** How the frame's feature registration tracked it (ROI modes: its ROI,
   *  the anchors alone, or the whole image). */
  ETrackingMethod featureMethodOf(const TFrameWork& w) const;
  /** Non-strict ROI mode with roi_extraction = region or flow. */
  bool describesRegions() const;
  /** roi_extraction = flow (non-strict ROI modes). Flow frames also follow
   *  the reference keyframe's ROI with the predicted motion; stage 1 runs
   *  only where it cannot, and for keyframes. */
  bool followsWithFlow() const;
  /** Stage 1 on the frame now, if prepare() did not run it. */
  void detectRoi(TFrameWork& w) const;
  /** The frame's ROI: prepare()'s, or for a flow frame its reference
   *  keyframe's followed with the predicted motion (stage 1 where that
   *  fails and on the other frames of flow mode). Needs w.flowFrame. */
  void takeRoi(TFrameWork& w) const;
  /** The frame can follow its reference keyframe by optical flow (both
   *  pyramids exist). */
  bool flowAvailable(const TFrameWork& w) const;
  /** roi_extraction = flow: follows the reference keyframe's anchors
   *  outside `described` into the frame and makes w.cur the frame's set
   *  plus theirs (FlowTracking.h). */
  void followReference(TFrameWork& w, const cv::Rect& described) const;
  /** roi_extraction = flow: an expected keyframe whose whole-image
   *  registration failed or is weak is registered again with the reference
   *  keyframe's anchors followed into it (all of them) as known pairs. */
  void rescueWithAnchors(TFrameWork& w) const;
  /** w.cur from w.regionSet and the followed features, as lifted now. */
  void rebuildFollowedSet(TFrameWork& w) const;
  /** roi_extraction = flow: the new keyframe's anchors (FlowTracking.h). */
  void setAnchors(TKeyframe& kf, TFrameWork& w) const;
  void startMap(TFrameWork& w);
  void predictMotion(TFrameWork& w) const;
  void trackFeatures(TFrameWork& w);
  /** Registers query against the recent keyframes, newest first (w.reg,
   *  w.ref, the match count). */
  void registerWithRecent(const TKeyframe& query, TFrameWork& w) const;
  void refineRollingShutter(TFrameWork& w);
  void refineWithDepth(TFrameWork& w) const;
  /** icp_fusion = measured: the scale refineWithDepth fuses its ICP
   *  (w.refineIcp) at, after booking its disagreement with the features
   *  (IcpConsistency.h); nullopt where it does not join, or where the
   *  colour image sided with it and it replaced the features. */
  std::optional<double> measuredIcpScale(TFrameWork& w, bool weak, double pairShare) const;
  /** icp_colour_check: whether the colour image sides with depth ICP's
   *  estimate icpT against the frame's feature registration (w.reg, against
   *  keyframe w.ref; PhotometricCheck.h). */
  bool colourSidesWithIcp(const TFrameWork& w, const geometry::TRigid& icpT) const;
  /** icp_fusion = measured: whether this registration runs depth ICP on
   *  pairShare of its pairs (as a probe too, unless ignoreProbe). */
  bool icpWorthRunning(double pairShare, bool ignoreProbe = false) const;
  /** Pose from the registration, or from the fallbacks; false when Lost. */
  bool resolvePose(TFrameWork& w);
  // bridge_previous_frame (StageBridge.cpp).
  /** Features failed against every keyframe: registers the frame against
   *  the previous frame and chains that to the keyframe it tracked (w.reg,
   *  w.ref, w.bridged); false when there is no such frame or no match. */
  bool bridgeFromPrevious(TFrameWork& w) const;
  /** Keeps a tracked, non-keyframe frame for the next one to bridge with
   *  (or forgets the previous one). */
  void rememberFrame(TFrameWork& w);
  bool needsKeyframe(const TFrameWork& w) const;
  /** The keyframe criteria for the frame at `pose` (its measured or its
   *  predicted one), with `fewInliers` as measured. */
  bool keyframeCriteria(
      const TFrameWork& w, const mrpt::poses::CPose3D& pose, bool fewInliers) const;
  /** keyframe_prediction: whether the predicted pose already meets the
   *  keyframe criteria (region and flow extraction only). */
  bool expectsKeyframe(const TFrameWork& w) const;
  /** keyframe_policy = overlap. */
  bool usesOverlapPolicy() const { return m_options.keyframe_policy == "overlap"; }
  void makeKeyframeConstraints(TFrameWork& w);
  void insertKeyframe(TFrameWork& w, const mrpt::poses::CPose3D& pose);
  /** The tracking region a new keyframe hands to the next frames. */
  cv::Rect keyframeRegion(const TFrameWork& w) const;
  /** Drops what only the recent keyframes keep (recent_keyframes + 1). */
  void trimRecentKeyframeStores();
  /** Remembers the frame as the last tracked one, counts it, times it. */
  TFrameResult finish(TFrameWork& w);

  TOptions m_options;
  mrpt::poses::CPose3D m_initialPose;
  std::deque<TKeyframe> m_keyframes;
  TStats m_stats;
  std::unique_ptr<TImpl> m_impl;
};
}  // namespace roislam::frontend
