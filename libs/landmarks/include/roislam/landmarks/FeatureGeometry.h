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
 *  metres (0 = none), registered to the colour camera; a keypoint without a
 *  reading at its pixel takes the median of the valid readings in its 3x3
 *  neighbourhood. Readings outside [minDepth, maxDepth] are ignored. Pixels are
 *  undistorted with the camera's distortion before back-projection. */
TFeatureDepth featureDepth(
    const std::vector<cv::KeyPoint>& keypoints, const cv::Mat& depth,
    const mrpt::img::TCamera& camera, double minDepth, double maxDepth);

/** Optical-frame point -> MRPT camera frame (x forward, y left, z up). */
mrpt::math::TPoint3D opticalToMrptCamera(const mrpt::math::TPoint3D& p);

/** Pose of MRPT's camera frame (x forward) expressed in the optical frame:
 *  use as sensorLocationOnRobot when the robot frame is the optical camera
 *  frame (the TUM ground-truth convention). Equals -CPose3D(0,0,0,-90deg,0,-90deg),
 *  printed "[0 0 0 90 -90 0]" (yaw pitch roll in degrees). */
mrpt::poses::CPose3D mrptCameraInOptical();
}  // namespace roislam::landmarks
