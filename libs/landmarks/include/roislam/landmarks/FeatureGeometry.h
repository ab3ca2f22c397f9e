/* 3-D geometry of features from a registered depth image, and the frame
 * conventions of the landmark observations. Used by CRoiLandmarkTracker and
 * CObservationProcessor.
 *
 * Frames: the optical frame (OpenCV/TUM: x right, y down, z forward) holds
 * back-projected points; MRPT's camera/sensor frame (x forward, y left, z up)
 * holds the bearing-range measurements. x_mrpt = z_opt, y_mrpt = -x_opt,
 * z_mrpt = -y_opt.
 */
#pragma once

#include <mrpt/img/TCamera.h>
#include <mrpt/math/TPoint3D.h>
#include <mrpt/poses/CPose3D.h>

#include <cmath>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

namespace roislam::landmarks
{
struct TFeatureDepth
{
  /** Features with a valid depth reading. */
  int valid = 0;
  /** Mean and median depth (z) of those features, metres; NaN when none. */
  double mean = 0;
  double median = 0;
  /** Component-wise median of their 3-D points in the optical frame. */
  std::optional<mrpt::math::TPoint3D> position;
};

/** Depth statistics and robust 3-D position of keypoints. depth: CV_32FC1
 *  metres (0 = none), registered to the colour camera; which keypoints have a
 *  depth is the project's one rule (geometry::liftPixels: the reading at the
 *  keypoint's pixel within [minDepth, maxDepth], not on a depth edge); rays
 *  go through the undistorted pixels. */
TFeatureDepth featureDepth(
    const std::vector<cv::KeyPoint>& keypoints, const cv::Mat& depth,
    const mrpt::img::TCamera& camera, double minDepth, double maxDepth);

/** Depth statistics and median position of points (invalid ones skipped). */
TFeatureDepth depthStatistics(const std::vector<mrpt::math::TPoint3D>& points);

/** The optical-frame 3-D point of each keypoint (same rules as
 *  featureDepth); NaN coordinates where there is no valid depth. */
std::vector<mrpt::math::TPoint3D> featurePoints(
    const std::vector<cv::KeyPoint>& keypoints, const cv::Mat& depth,
    const mrpt::img::TCamera& camera, double minDepth, double maxDepth);

inline bool isValidPoint(const mrpt::math::TPoint3D& p)
{
  return std::isfinite(p.z);
}

struct TRigidFit
{
  /** pose such that a_i = pose (+) b_i for the inlier pairs. */
  mrpt::poses::CPose3D pose;
  int inliers = 0;
  /** Valid pairs considered. */
  int pairs = 0;
  /** RMS residual of the inliers, metres. */
  double rms = 0;
};

/** Rigid transform between corresponding 3-D points by
 *  matching::CRigidTransformRansac (minimal 3-pair samples, deterministic
 *  seed, at most `iterations` hypotheses, inlier distance `threshold` in
 *  metres, least-squares refits on the inliers). Pairs with an invalid point
 *  are ignored. nullopt with fewer than 3 valid pairs or agreeing inliers. */
std::optional<TRigidFit> fitRigid(
    const std::vector<mrpt::math::TPoint3D>& a, const std::vector<mrpt::math::TPoint3D>& b,
    double threshold, int iterations = 100);

/** Optical-frame point -> MRPT camera frame (x forward, y left, z up). */
mrpt::math::TPoint3D opticalToMrptCamera(const mrpt::math::TPoint3D& p);

/** Pose of MRPT's camera frame (x forward) expressed in the optical frame:
 *  use as sensorLocationOnRobot when the robot frame is the optical camera
 *  frame (the TUM ground-truth convention). Equals -CPose3D(0,0,0,-90deg,0,-90deg),
 *  printed "[0 0 0 90 -90 0]" (yaw pitch roll in degrees). */
mrpt::poses::CPose3D mrptCameraInOptical();
}  // namespace roislam::landmarks
