/* The pinhole part of a camera (no distortion): projection of optical-frame
 * points and back-projection of undistorted pixels. Used by the keypoint
 * lifting (KeypointLifting.h), the front end's registration and
 * rolling-shutter model, and the landmarks.
 */
#pragma once

#include <Eigen/Dense>
#include <opencv2/core.hpp>

namespace roislam::geometry
{
struct TPinhole
{
  double fx = 1, fy = 1, cx = 0, cy = 0;

  /** The optical-frame point (x right, y down, z forward) at depth z seen
   *  at undistorted pixel u. */
  Eigen::Vector3d backProject(const cv::Point2f& u, double z) const
  {
    return {(u.x - cx) / fx * z, (u.y - cy) / fy * z, z};
  }
  /** The undistorted pixel of optical-frame point X (X.z() > 0). */
  cv::Point2f project(const Eigen::Vector3d& X) const
  {
    return {
        static_cast<float>(fx * X.x() / X.z() + cx), static_cast<float>(fy * X.y() / X.z() + cy)};
  }
};
}  // namespace roislam::geometry
