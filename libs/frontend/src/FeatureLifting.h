/* Keypoints to 3-D points with the registered depth image: which keypoints
 * have usable depth, and the feature sets (TKeyframe layout) built from them.
 */
#pragma once

#include <roislam/features/TFeatureSet.h>
#include <roislam/frontend/CRgbdOdometry.h>
#include <roislam/frontend/TKeyframe.h>

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
  /** Undistorted pixel of every extracted keypoint. */
  std::vector<cv::Point2f> undistorted;
};

/** depth: CV_32FC1 metres, registered with the colour image; K, dist: the
 *  colour camera's intrinsics and distortion (OpenCV layout). */
TLiftedFeatures liftFeatures(
    const features::TFeatureSet& all, const cv::Mat& depth, const cv::Mat& K, const cv::Mat& dist,
    const CRgbdOdometry::TOptions& o);

/** The features at idx (indices into all, each in lifted.valid) with their
 *  3-D points in the camera's optical frame and undistorted pixels. Only the
 *  feature fields of the TKeyframe are filled. */
TKeyframe makeFeatureSet(
    const features::TFeatureSet& all, const TLiftedFeatures& lifted, const std::vector<int>& idx,
    const cv::Mat& depth, const TPinhole& pinhole);
}  // namespace roislam::frontend::detail
