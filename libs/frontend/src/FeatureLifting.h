/* Keypoints to 3-D points with the registered depth image: which keypoints
 * have usable depth, the rolling-shutter correction of their rays and points,
 * and the feature sets (TKeyframe layout) built from them.
 *
 * Rolling shutter: a Kinect-type colour camera exposes its rows one after the
 * other, so while the camera turns, each row sees the scene from a slightly
 * different pose. On fr1/rpy (about 60 deg/s) this is the largest error left
 * in a frame-to-keyframe registration: the global-shutter motion that best
 * explains the sheared image is wrong by up to a degree, and the translation
 * follows it by centimetres. rectifyRollingShutter() moves every keypoint's
 * point (and so its pixel) by the motion the camera made between its row's
 * time and the middle row's, so the set looks as if taken at once at the
 * middle row's time. The depth image, registered to the colour one, is read
 * at the keypoint's own pixel (its rows are read out in step, to first order).
 */
#pragma once

#include <roislam/features/TFeatureSet.h>
#include <roislam/frontend/CRgbdOdometry.h>
#include <roislam/frontend/TKeyframe.h>

#include <Eigen/Dense>
#include <opencv2/core.hpp>
#include <vector>

#include "ReprojectionRefinement.h"

namespace roislam::frontend::detail
{
struct TLiftedFeatures
{
  /** Indices (into the extracted set) of keypoints with valid depth: within
   *  [min_depth_m, max_depth_m] and, if depth_discontinuity_m > 0, not on a
   *  depth edge (3x3 neighbourhood spread <= depth_discontinuity_m * depth). */
  std::vector<int> valid;
  /** Undistorted pixel of every extracted keypoint, after the rolling-shutter
   *  correction (rectifyRollingShutter; equal to raw without one). */
  std::vector<cv::Point2f> undistorted;
  /** Depth [m] of every extracted keypoint, corrected like undistorted; set
   *  at the indices in valid only. */
  std::vector<float> z;
  /** The same before any rolling-shutter correction. */
  std::vector<cv::Point2f> rawUndistorted;
  std::vector<float> rawZ;
  /** Time of each keypoint's row relative to the middle row, as a fraction of
   *  the readout time: -0.5 (first row) .. 0.5 (last row). */
  std::vector<float> rowFraction;
};

/** depth: CV_32FC1 metres, registered with the colour image; K, dist: the
 *  colour camera's intrinsics and distortion (OpenCV layout). */
TLiftedFeatures liftFeatures(
    const features::TFeatureSet& all, const cv::Mat& depth, const cv::Mat& K, const cv::Mat& dist,
    const CRgbdOdometry::TOptions& o);

/** How fast the camera moves, in its own frame: angular (rad/s) and linear
 *  (m/s) velocity. */
struct TCameraRate
{
  Eigen::Vector3d omega = Eigen::Vector3d::Zero();
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();
  bool isZero() const { return omega.isZero() && linear.isZero(); }
};

/** A point seen s seconds after the middle row (its raw undistorted pixel and
 *  depth), carried into the middle row's camera: exp(omega s) X + linear s. */
Eigen::Vector3d rectifyPoint(
    const cv::Point2f& rawPixel, double rawZ, double s, const TCameraRate& rate,
    const TPinhole& pinhole);

/** Recomputes lifted.undistorted and lifted.z at the valid indices from the
 *  raw ones: a point seen s = rowFraction * readout_s seconds after the
 *  middle row is carried into the middle row's camera, X' = exp(omega s) X +
 *  linear s, and its pixel is X' projected. A zero rate or readout_s = 0
 *  restores the raw values. */
void rectifyRollingShutter(
    TLiftedFeatures& lifted, const TCameraRate& rate, double readout_s, const TPinhole& pinhole);

/** The features at idx (indices into all, each in lifted.valid) with their
 *  3-D points in the camera's optical frame and undistorted pixels. Only the
 *  feature fields of the TKeyframe are filled. */
TKeyframe makeFeatureSet(
    const features::TFeatureSet& all, const TLiftedFeatures& lifted, const std::vector<int>& idx,
    const TPinhole& pinhole);

/** Recomputes k's points and pixels (k made by makeFeatureSet with the same
 *  idx) from lifted, after a new rolling-shutter correction; the features,
 *  and so any index built over them, stay. */
void updateFeatureSetPoints(
    TKeyframe& k, const TLiftedFeatures& lifted, const std::vector<int>& idx,
    const TPinhole& pinhole);
}  // namespace roislam::frontend::detail
