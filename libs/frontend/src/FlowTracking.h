/* Private: the ROI modes' way to see the rest of the image without describing
 * it (roi_extraction = flow). A keyframe keeps points good to track with
 * their depth, a window apart: its anchors (flow_anchors: its own strongest
 * features, spacedStrongest, or Shi-Tomasi corners found for the purpose,
 * anchorCandidates). An ordinary frame describes its
 * ROI only; the reference keyframe's anchors are followed into it by
 * pyramidal Lucas-Kanade optical flow, each started where the predicted
 * motion puts its 3-D point. Their correspondence is known, so they are not
 * matched: they join the ROI's matches in one RANSAC and refinement. The
 * work is the ROI's description plus a few hundred 21 x 21 patches, not the
 * image's detection and description.
 */
#pragma once

#include <mrpt/poses/CPose3D.h>
#include <roislam/features/TFeatureSet.h>
#include <roislam/frontend/TKeyframe.h>

#include <opencv2/core.hpp>
#include <vector>

namespace roislam::frontend::detail
{
/** Lucas-Kanade settings: a 21 x 21 window over 4 pyramid levels follows
 *  about 8 x 10 px of motion beyond the prediction. Anchors are at least a
 *  window apart, so that no two share their window. */
struct TFlowParams
{
  int window = 21;
  int levels = 3;  //!< maxLevel: levels + 1 pyramid images
  /** Shi-Tomasi quality: corners weaker than this share of the frame's
   *  strongest are not anchors (OpenCV's customary 0.01). Anchors are found
   *  at half resolution, which keeps fewer of them (fr1 excerpts, every
   *  8th-12th frame: 158 / 181 a frame against 203 / 206 at full
   *  resolution); 0.005 there keeps as many as at full resolution but
   *  tracked worse (the odometry's ATE worse on 9 of 12 fr1 runs), the weak
   *  corners being the ones Lucas-Kanade follows least well. */
  double anchorQuality = 0.01;
};

/** An image pyramid as cv::buildOpticalFlowPyramid makes it, its first
 *  level the image halved flowShift() times. */
using TFlowPyramid = std::vector<cv::Mat>;

/** How many times an image of this size is halved before it is tracked:
 *  until it is under 1280 px wide (at least 640). The window, the pyramid
 *  depth and the anchors' spacing were measured at 640 x 480 (fr1); a
 *  camera of twice the width (a Kinect v2's 1920 x 1080 colour) then follows
 *  the same part of the scene with each window and about as many anchors,
 *  instead of four times as many at 10 us each (rgbd-simul 1920 x 1080:
 *  337 anchors a frame, 13 ms of flow). 640 x 480 and 960 x 540: 0. */
int flowShift(const cv::Size& image);

/** withDerivatives: also each level's Scharr derivatives, which
 *  Lucas-Kanade needs of the image it follows from (a keyframe's) and would
 *  otherwise compute on every call; the image followed into (every frame)
 *  needs none, and building them cost 0.2 ms a frame against 0.08 for the
 *  levels alone (fr1, 2 cores). */
TFlowPyramid flowPyramid(const cv::Mat& grey, const TFlowParams& p, bool withDerivatives);

/** The same from the image already halved flowShift(image) times (the
 *  features' working image when its shift is the flow's: one pyrDown less). */
TFlowPyramid flowPyramidOfTracked(
    const cv::Mat& tracked, const TFlowParams& p, bool withDerivatives);

/** A full-resolution pixel position at flowShift() = shift, and back (pixel
 *  centres: (u + 0.5) / 2^shift - 0.5). */
cv::Point2f toFlowLevel(const cv::Point2f& u, int shift);
cv::Point2f fromFlowLevel(const cv::Point2f& u, int shift);

/** Candidate anchors of a keyframe image: Shi-Tomasi corners (found at
 *  half the tracked resolution, flowShift()), a window of the tracked
 *  image apart, as full-resolution keypoints (size 0: not described). */
features::TFeatureSet anchorCandidates(const cv::Mat& grey, const TFlowParams& p);

/** flow_anchors = features: indices of `keypoints` (the keyframe's own
 *  features with depth), strongest response first, each at least a window
 *  of the tracked image (flowShift) from every one taken before. */
std::vector<int> spacedStrongest(
    const std::vector<cv::KeyPoint>& keypoints, const cv::Size& image, const TFlowParams& p);

/** The keyframe's anchors followed into the current frame. */
struct TFlowTracks
{
  /** Keypoints at the followed (distorted) positions; descriptors are zero
   *  rows of the keyframe features' type (never matched). */
  features::TFeatureSet set;
  /** For each followed anchor, its index in the keyframe's anchors. */
  std::vector<int> anchorIndex;
};

/** Follows kf's anchors whose predicted position lies inside the image and
 *  outside `described` from kf's image (kfPyramid) into the current one.
 *  predictedRel: the current frame's pose relative to kf; K, dist: the
 *  colour camera (OpenCV layout; images are distorted); image: the frame's
 *  full-resolution size (the pyramids are flowShift(image) levels below);
 *  described: the part of the frame whose features were described (empty:
 *  none). */
TFlowTracks followAnchors(
    const TKeyframe& kf, const TFlowPyramid& kfPyramid, const TFlowPyramid& curPyramid,
    const mrpt::poses::CPose3D& predictedRel, const cv::Mat& K, const cv::Mat& dist,
    const cv::Size& image, const cv::Rect& described, const TFlowParams& p);

/** kf as the registration against its anchors sees it: its features'
 *  points and pixels followed by its anchors' (the anchors' pair indices
 *  are kf.points.size() + anchor index). */
TKeyframe withAnchors(const TKeyframe& kf);
}  // namespace roislam::frontend::detail
