/* Result types of the SLAM front end (CRgbdOdometry): how one frame was
 * tracked, the relative-pose constraints a new keyframe brings, and the
 * keyframe-to-keyframe registration used by the back end to verify loop
 * closures. Consumed by the graph-SLAM back end and the apps.
 *
 * Pose conventions (everywhere in roislam::frontend): TUM-style camera optical
 * frame (x right, y down, z forward). A world pose P maps camera coordinates to
 * world coordinates (p_world = P (+) p_cam). A relative pose of B with respect
 * to A is R = A^-1 (+) B, i.e. B = A (+) R.
 */
#pragma once

#include <mrpt/math/CMatrixFixed.h>
#include <mrpt/poses/CPose3D.h>

#include <cstddef>
#include <opencv2/core/types.hpp>
#include <optional>
#include <string>
#include <vector>

namespace roislam::frontend
{
/** How a frame's pose was obtained. */
enum class ETrackingMethod
{
  /** First frame of the run: pose = initial pose, becomes keyframe 0. */
  Initial,
  /** Full-image features: mode traditional, and in ROI modes a frame
   *  expected to become a keyframe (keyframe_prediction), which describes
   *  the whole image by design. */
  Features,
  /** ROI features (modes roi_small / roi_big / roi). */
  RoiFeatures,
  /** roi_extraction = flow: the reference keyframe's anchors followed by
   *  optical flow, without the ROI's features (none described, or too few). */
  Flow,
  /** ROI mode, but the frame had no ROI or too few ROI features: tracked with
   *  full-image features instead (never in strict_roi mode). */
  FullImageFallback,
  /** Features failed (featureless scene): projective point-to-plane ICP on the
   *  decimated depth image against the reference keyframe. */
  DepthIcp,
  /** Features and ICP failed: pose extrapolated with the last inter-frame
   *  motion (never in strict_roi mode). */
  ConstantVelocity,
  /** strict_roi only: no ROI features (or registration failed): the frame
   *  has NO pose (TFrameResult::pose is nullopt). */
  Lost
};

/** "initial" | "features" | "roi" | "flow" | "full_image_fallback" | "depth_icp" |
 *  "constant_velocity" | "lost". */
std::string toString(ETrackingMethod m);

/** 6x6 information matrix in MRPT's CPose3DPDFGaussianInf convention: the
 *  inverse covariance of the 6-vector (x, y, z, yaw, pitch, roll) of the
 *  relative pose, metres and radians. */
using TInformation66 = mrpt::math::CMatrixDouble66;

/** A relative-pose measurement between two keyframes. */
struct TKeyframeConstraint
{
  /** Older keyframe id (the reference). */
  std::size_t fromKeyframe = 0;
  /** Newer keyframe id. */
  std::size_t toKeyframe = 0;
  /** Pose of `to` relative to `from`: pose(to) = pose(from) (+) relativePose. */
  mrpt::poses::CPose3D relativePose;
  TInformation66 information;
  /** TFrameResult::relativeEdgeInformation of this constraint. */
  TInformation66 edgeInformation;
  /** How it was measured (Features/RoiFeatures/Flow/FullImageFallback/DepthIcp/
   *  ConstantVelocity). A ConstantVelocity constraint carries a weak
   *  information (see TOptions::constant_velocity_information_scale). */
  ETrackingMethod method = ETrackingMethod::Features;
  /** Feature inliers (ICP: number of point correspondences; 0 for CV). */
  std::size_t inliers = 0;
};

/** Result of registering one keyframe against another (loop closure check). */
struct TRelativePoseEstimate
{
  /** Pose of B relative to A: pose(B) = pose(A) (+) pose. */
  mrpt::poses::CPose3D pose;
  TInformation66 information;
  /** TFrameResult::relativeEdgeInformation of this estimate. */
  TInformation66 edgeInformation;
  /** Putative descriptor matches and RANSAC/refinement inliers. */
  std::size_t matches = 0;
  std::size_t inliers = 0;
  /** RMS 3-D distance of the inliers after refinement, metres. */
  double rmse_m = 0;
  /** RMS reprojection error of the inliers after refinement, pixels. */
  double rmse_px = 0;
};

/** Why a ROI-mode frame's features were extended beyond its tracking region
 *  (each frame at most once), or that stage 2 ran on the whole image. */
enum class EExtension
{
  /** ROI-only frame: features described in the tracking region alone. */
  None,
  /** The whole image at once: traditional mode, strict_roi, or
   *  roi_extraction = image. */
  WholeImage,
  /** No ROI was detected. */
  NoRoi,
  /** The region had fewer than min_roi_features features with depth. */
  FewRoiFeatures,
  /** The region's features did not register against any recent keyframe. */
  RoiFailed,
  /** They registered, but left the pose poorly determined (max_roi_sigma_m,
   *  max_roi_sigma_deg, min_roi_inliers). */
  RoiWeak,
  /** The frame became a keyframe (keyframes store the whole image's
   *  features, for later frames and loop closures). */
  Keyframe,
  /** keyframe_prediction: the predicted pose met the keyframe criteria, so
   *  the whole image was described at once, before tracking, and tracked
   *  with. */
  ExpectedKeyframe
};

/** "none" | "whole_image" | "no_roi" | "few_roi_features" | "roi_failed" |
 *  "roi_weak" | "keyframe" | "expected_keyframe". */
std::string toString(EExtension e);

/** What stage 2 described for one frame: its cost scales with these. */
struct TDescribedWork
{
  /** The tracking region (the ROI grown to track with); empty when none. */
  cv::Rect region;
  /** Pixels the detector ran on for the region (region + support margin),
   *  and the features it kept there. */
  std::size_t regionPixels = 0, regionFeatures = 0;
  /** The same for the rest of the image (or the whole image). */
  std::size_t extensionPixels = 0, extensionFeatures = 0;
  EExtension extension = EExtension::None;
  /** Described pixels over the image's pixels (> 1 possible: margins). */
  double describedFraction(const cv::Size& image) const
  {
    return image.area() > 0 ? static_cast<double>(regionPixels + extensionPixels) / image.area()
                            : 0.0;
  }
};

/** Per-stage wall-clock times of one process() call, milliseconds. */
struct TStageTimes
{
  double roi_ms = 0;       //!< ROI detection (ROI modes)
  double extract_ms = 0;   //!< feature detection + description (once per frame)
  double lift_ms = 0;      //!< undistortion + depth lookup of keypoints
  double match_ms = 0;     //!< descriptor matching (all keyframes tried)
  double flow_ms = 0;      //!< optical flow of keyframe features (roi_extraction = flow)
  double ransac_ms = 0;    //!< 3-D RANSAC + refinement
  double icp_ms = 0;       //!< depth ICP fallback (and ICP maps of new keyframes)
  double keyframe_ms = 0;  //!< new keyframe: constraints to recent keyframes
  /** All front-end work for the frame: prepare() (grey image, stage 1),
   *  wherever it ran, and the whole process() call; decoding excluded. */
  double total_ms = 0;
};

/** Everything CRgbdOdometry::process() reports about one frame. */
struct TFrameResult
{
  std::size_t frameIndex = 0;  //!< TRGBDFrame::index
  double timestamp = 0;        //!< TRGBDFrame::timestamp (s)

  ETrackingMethod method = ETrackingMethod::Lost;
  /** World pose of the camera; nullopt only when method == Lost. */
  std::optional<mrpt::poses::CPose3D> pose;

  /** Reference keyframe the pose was measured against (for a new keyframe:
   *  the keyframe it was tracked from, not itself; for frame 0: 0). Undefined
   *  (0) when Lost. */
  std::size_t referenceKeyframe = 0;
  /** Pose relative to the reference keyframe: pose = kf.pose (+) relativePose. */
  mrpt::poses::CPose3D relativePose;
  /** Information of relativePose (CPose3DPDFGaussianInf convention). */
  TInformation66 relativeInformation;
  /** The estimator's information of relativePose in the parametrisation of
   *  MRPT's SPA (pseudo-log [x y z rx ry rz] of the right perturbation): the
   *  graph edge's with [GraphSlam] edge_information = estimator. */
  TInformation66 relativeEdgeInformation;

  /** This frame became a keyframe (id newKeyframeId). */
  bool isNewKeyframe = false;
  /** The frame's features no longer registered against any keyframe and
   *  were registered against the previous frame, chained to the keyframe
   *  that one tracked (TOptions::bridge_previous_frame); it became a
   *  keyframe. */
  bool bridged = false;
  /** Of this keyframe's constraints, those chained through the previous
   *  frame (its own registration against their keyframe failed). */
  std::size_t bridgedConstraints = 0;
  /** A feature registration combined with depth ICP: it left the pose
   *  poorly determined (TOptions::icp_refine_sigma_m), or measured fusion
   *  found ICP worth it (TOptions::icp_fusion). */
  bool icpRefined = false;
  /** Measured fusion: the features disagreed with depth ICP beyond ICP's
   *  model, the colour image sided with ICP, and ICP's estimate replaced
   *  theirs (PhotometricCheck.h); icpRefined is set too. */
  bool icpOverruledFeatures = false;
  /** Depth ICP's estimate replaced the features': where the colour image
   *  sided with it (icpOverruledFeatures), or where the two disagreed beyond
   *  ICP's scaled model and ICP was the better determined. The keyframe
   *  edge then keeps ICP's estimate. */
  bool icpReplacedFeatures = false;
  /** Depth ICP's share of the registration's information (its scaled
   *  information over the fused one, tr(Hicp / k * H^-1) / 6): 1 where it
   *  replaced the features (icpReplacedFeatures), 0 where it did not join.
   *  Above 1/2 ICP carries the frame, and a weak ROI makes no keyframe
   *  (TOptions::keyframe_on_weak_roi). */
  double icpInformationShare = 0;
  /** The share of its pairs the frame's refinement ICP used (1, or 0.25
   *  where measured fusion found ICP's error mostly bias: StageRefine.cpp);
   *  0 when none ran. */
  double icpPairShare = 0;
  /** Measured fusion's scale k of ICP's covariance after this frame's
   *  comparison (IcpConsistency.h: 1 = as ICP's model claims, above 1
   *  trusted less, below 1 trusted more, down to 0.04 = every pair
   *  independent; infinity: of no use beside the features); 0 while none
   *  is known, when no ICP ran or it found no alignment, or outside
   *  measured fusion. */
  double icpScale = 0;
  /** The features' and ICP's covariance scales fitted jointly from their
   *  recent disagreements (CIcpConsistency::jointScales(), measured
   *  fusion); 0 while unknown: how far the tracked frames' registrations
   *  are from their claimed covariance, each, instead of booking every
   *  disagreement against ICP (icpScale). Reported, not used. */
  double featureScale = 0, icpJointScale = 0;
  std::size_t newKeyframeId = 0;
  /** For a new keyframe (except the first): constraints from the recent
   *  keyframes to it. The first entry is always from referenceKeyframe (the
   *  odometry edge, exists for every non-Lost method); further entries from up
   *  to TOptions::recent_keyframes other recent keyframes that registered. */
  std::vector<TKeyframeConstraint> constraints;

  // Counts.
  std::size_t features = 0;           //!< extracted on the whole image
  std::size_t featuresWithDepth = 0;  //!< of those, with valid depth
  std::size_t roiFeatures = 0;        //!< with valid depth inside the ROI
  std::size_t trackingFeatures = 0;   //!< the set actually matched
  /** roi_extraction = flow: reference-keyframe features followed into the
   *  frame by optical flow (outside the region; not described, not matched). */
  std::size_t flowTracks = 0;
  std::size_t matches = 0;  //!< ratio-test matches to the reference
  std::size_t inliers = 0;  //!< after RANSAC + refinement (ICP: pairs)
  /** The ROI found in this frame: ROI modes, and keyframes of the
   *  traditional mode (their ROI is the back end's landmark). */
  std::optional<cv::Rect> roi;
  /** What stage 2 described (ROI modes: region, extension and why). */
  TDescribedWork work;
  /** Image size (for work.describedFraction()). */
  cv::Size imageSize;

  TStageTimes times;
};
}  // namespace roislam::frontend
