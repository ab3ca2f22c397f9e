/* Keypoints to 3-D points with the registered depth image: which keypoints
 * have usable depth (the project's one depth rule, geometry::liftPixels), and
 * the feature sets (TKeyframe layout) built from them.
 * The rolling-shutter correction of the lifted points is in RollingShutter.h.
 */
#pragma once

#include <roislam/features/TFeatureSet.h>
#include <roislam/frontend/CRgbdOdometry.h>
#include <roislam/frontend/TKeyframe.h>
#include <roislam/geometry/KeypointLifting.h>

#include <opencv2/core.hpp>
#include <vector>

#include "ReprojectionRefinement.h"

namespace roislam::frontend::detail
{
/** How fast the camera moves, in its own frame: angular (rad/s) and linear
 *  (m/s) velocity. */
struct TCameraRate
{
  Eigen::Vector3d omega = Eigen::Vector3d::Zero();
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();
  bool isZero() const { return omega.isZero() && linear.isZero(); }
};

struct TLiftedFeatures
{
  /** Indices (into the extracted set) of keypoints with valid depth: within
   *  [min_depth_m, max_depth_m] and, if depth_discontinuity_m > 0, not on a
   *  depth edge (3x3 neighbourhood spread <= depth_discontinuity_m * depth). */
  std::vector<int> valid;
  /** Undistorted pixel of every extracted keypoint, after the rolling-shutter
   *  correction (RollingShutter.h; equal to raw without one). */
  std::vector<cv::Point2f> undistorted;
  /** Depth [m] of every extracted keypoint, corrected like undistorted; set
   *  at the indices in valid only. */
  std::vector<float> z;
  /** The same before any rolling-shutter correction (after the depth-time
   *  one, RollingShutter.h alignDepthTime). */
  std::vector<cv::Point2f> rawUndistorted;
  std::vector<float> rawZ;
  /** Depth read at the keypoint's own pixel, before any correction. */
  std::vector<float> readZ;
  /** Time of each keypoint's row relative to the middle row, as a fraction of
   *  the readout time: -0.5 (first row) .. 0.5 (last row). */
  std::vector<float> rowFraction;
  /** The camera's velocity the corrections used (RollingShutter.h
   *  rectifyRollingShutter records it); feature sets built from these
   *  points carry it (TKeyframe::angularRate, linearRate). */
  TCameraRate rate;
};

/** The front end's depth rule (geometry::liftPixels) from its options. */
geometry::TDepthRule depthRule(const CRgbdOdometry::TOptions& o);

/** depth: CV_32FC1 metres, registered with the colour image; K, dist: the
 *  colour camera's intrinsics and distortion (OpenCV layout). */
TLiftedFeatures liftFeatures(
    const features::TFeatureSet& all, const cv::Mat& depth, const cv::Mat& K, const cv::Mat& dist,
    const CRgbdOdometry::TOptions& o);

/** Appends b (lifted from features that follow a's `offset` features in the
 *  frame's set) to a. */
void appendLifted(TLiftedFeatures& a, const TLiftedFeatures& b, int offset);

/** The features at idx (indices into all, each in lifted.valid) with their
 *  3-D points in the camera's optical frame and undistorted pixels. Only the
 *  feature fields of the TKeyframe are filled. */
TKeyframe makeFeatureSet(
    const features::TFeatureSet& all, const TLiftedFeatures& lifted, const std::vector<int>& idx,
    const TPinhole& pinhole);

/** Sets k's velocity (TKeyframe::angularRate, linearRate) to rate. */
void setKeyframeRate(TKeyframe& k, const TCameraRate& rate);

/** Recomputes k's points, pixels and velocity (k made by makeFeatureSet
 *  with the same idx) from lifted, after a new rolling-shutter correction;
 *  the features, and so any index built over them, stay. */
void updateFeatureSetPoints(
    TKeyframe& k, const TLiftedFeatures& lifted, const std::vector<int>& idx,
    const TPinhole& pinhole);
}  // namespace roislam::frontend::detail
