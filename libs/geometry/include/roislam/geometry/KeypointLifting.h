/* Keypoints to 3-D with a registered depth image: the one depth rule of the
 * project, used by the front end (FeatureLifting.h) and the landmarks
 * (FeatureGeometry.h).
 *
 * The rule: the depth image is registered to the distorted colour image, so
 * a keypoint's depth is read at its own (rounded) pixel, and its ray goes
 * through its undistorted pixel. The reading must lie in [min_depth_m,
 * max_depth_m] and, with depth_discontinuity_m > 0, the 3x3 neighbourhood
 * must be complete and spread by at most depth_discontinuity_m per metre of
 * depth: a keypoint on a depth edge (an object's outline, the usual place
 * of corners) takes the depth of either side at random, so it gets none.
 * The landmarks formerly filled a missing reading with the median of its
 * 3x3 neighbours; they now use this rule without the edge test (figures in
 * libs/landmarks/src/FeatureGeometry.cpp).
 *
 * cv::rgbd::depthTo3dSparse (opencv_rgbd) was measured and not taken
 * (tests/benchmark/geometry_benchmark.cpp, Lift/...: 10 fr1/rpy frames, 600 ORB
 * keypoints): it reads the depth at the truncated pixel and casts the ray
 * through that same distorted pixel, with no edge test. Of the keypoints both
 * lift, 22 % read another depth and the points lie 8.7 mm (mean) and up to
 * 121 mm from these; it takes 11 us of CPU per frame against 43 us here
 * (mostly cv::undistortPoints), which a 30 ms frame does not notice.
 */
#pragma once

#include <roislam/geometry/TPinhole.h>

#include <opencv2/core.hpp>
#include <vector>

namespace roislam::geometry
{
struct TDepthRule
{
  /** Usable depth readings, metres. */
  double min_depth_m = 0.3;
  double max_depth_m = 4.0;
  /** Largest 3x3 depth spread per metre of depth; 0 = no edge test. */
  double depth_discontinuity_m = 0.05;
};

struct TLiftedPixels
{
  /** Indices (into the input pixels) of those with a depth by the rule. */
  std::vector<int> valid;
  /** Every input pixel undistorted (pixel units of the same camera matrix). */
  std::vector<cv::Point2f> undistorted;
  /** Depth in metres at the valid indices, 0 elsewhere. */
  std::vector<float> z;
};

/** depth: CV_32FC1 metres (0 = no reading) registered with the colour image;
 *  K: 3x3 camera matrix, dist: OpenCV distortion coefficients (empty = none).
 *  Throws std::invalid_argument on another depth type. */
/** The depth the rule accepts at pixel (u, v) of depth (CV_32FC1 metres),
 *  or 0: within [min_depth_m, max_depth_m], not on the outermost rows and
 *  columns, and (depth_discontinuity_m > 0) its 3x3 neighbourhood all read
 *  and spread by at most depth_discontinuity_m * depth. */
float depthByRule(const cv::Mat& depth, int u, int v, const TDepthRule& rule);

TLiftedPixels liftPixels(
    const std::vector<cv::Point2f>& pixels, const cv::Mat& depth, cv::InputArray K,
    cv::InputArray dist, const TDepthRule& rule);
}  // namespace roislam::geometry
