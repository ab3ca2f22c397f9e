/* A rigid motion as an Eigen rotation matrix and translation: the form the
 * numeric code works in (RANSAC, Gauss-Newton, ICP), converted to and from
 * MRPT's CPose3D at the interfaces. Used by the matching RANSAC, the front end
 * and the rigid alignment (RigidAlignment.h).
 */
#pragma once

#include <mrpt/poses/CPose3D.h>

#include <Eigen/Dense>

namespace roislam::geometry
{
/** x_a = R x_b + t. */
struct TRigid
{
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();

  Eigen::Vector3d operator*(const Eigen::Vector3d& p) const { return R * p + t; }
  TRigid inverse() const
  {
    TRigid o;
    o.R = R.transpose();
    o.t = -(o.R * t);
    return o;
  }

  static TRigid fromPose(const mrpt::poses::CPose3D& p);
  /** The pose with this rotation matrix as it is (no re-orthonormalisation). */
  mrpt::poses::CPose3D toPose() const;
};
}  // namespace roislam::geometry
