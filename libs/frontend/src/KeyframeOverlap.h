/* Private: how much of a keyframe's view a camera pose still sees, and the
 * keyframes that overlap a predicted view best. The adaptive keyframe policy
 * (TOptions::keyframe_policy = overlap) makes a keyframe when the view
 * overlap with the reference keyframe falls below keyframe_min_overlap, and
 * tracks each frame against the best-overlapping keyframe, so that a revisit
 * re-uses the keyframes made there before instead of making new ones.
 */
#pragma once

#include <mrpt/poses/CPose3D.h>
#include <roislam/frontend/TKeyframe.h>
#include <roislam/geometry/TPinhole.h>

#include <cstddef>
#include <deque>
#include <opencv2/core/types.hpp>
#include <vector>

namespace roislam::frontend::detail
{
/** Where a view is seen from: the camera, the image size and the depth range
 *  the front end uses features in. */
struct TViewModel
{
  geometry::TPinhole camera;
  cv::Size image;
  double minDepth = 0, maxDepth = 0;
};

/** Share (in [0, 1]) of the keyframe's feature points that a camera at
 *  `rel` (its pose relative to the keyframe: pose = kf.pose (+) rel) sees in
 *  front of it, within the depth range and inside the image; occlusion is
 *  ignored. At most `samples` points, evenly spaced, are tested (0 = all).
 *  0 for a keyframe without points. */
double viewOverlap(
    const TKeyframe& kf, const mrpt::poses::CPose3D& rel, const TViewModel& view,
    std::size_t samples = 0);

/** What makes a keyframe a good reference for a view: its view overlap, and
 *  optionally (> 0) how far it may be from the view's pose. */
struct TReferenceGate
{
  double minOverlap = 0;
  double maxDistance = 0, maxAngleRad = 0;
};

/** The keyframes to track a view at world pose `predicted` against, at most
 *  `n`: first those that pass `gate` (overlap of `samples` points each, and
 *  the bounds), newest first (the least drift to the view, and the ones with
 *  search indexes and ICP maps); then the others that overlap at all, best
 *  overlap first. A revisit, whose newest keyframes do not overlap, so gets
 *  the keyframes made there before. */
std::vector<std::size_t> referenceCandidates(
    const std::deque<TKeyframe>& keyframes, const mrpt::poses::CPose3D& predicted,
    const TViewModel& view, const TReferenceGate& gate, std::size_t n, std::size_t samples);

/** The keyframes within `maxDistance` [m] and `maxAngleRad` of world pose
 *  `pose`, nearest first: by the larger of the distance and the angle, each
 *  as a share of its bound (the motion policy's "place"). */
std::vector<std::size_t> keyframesNear(
    const std::deque<TKeyframe>& keyframes, const mrpt::poses::CPose3D& pose, double maxDistance,
    double maxAngleRad);
}  // namespace roislam::frontend::detail
