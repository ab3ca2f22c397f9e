/* SO(3) exponential and logarithm (rotation vector <-> matrix) for the
 * numeric code: the Gauss-Newton updates and information fusion of the front
 * end (RigidMath.h), the rolling-shutter model and the ICP's plausibility
 * check.
 *
 * Eigen::AngleAxisd rather than mrpt::poses::Lie::SO<3>::exp / log
 * (tests/benchmark/geometry_benchmark.cpp, So3Exp / So3Log: 1000 random axes
 * per angle, against Rodrigues' formula in long double). Largest entry error
 * of exp at 1e-9 / 1e-6 / 1e-3 / 1 rad: AngleAxis 2.5e-19 / 1.1e-16 /
 * 1.1e-16 / 2.2e-16, SO<3> 1.0e-25 / 7.5e-13 / 2.2e-16 / 2.2e-16 (its
 * small-angle series is cut too early around 1e-6 rad, the size of late
 * Gauss-Newton steps). Relative error of log: 1e-16 to 4e-16 for both.
 * Time per call (shared 2-core machine, median of 3): exp 9-21 ns against
 * 13-26 ns, log 31-39 ns against 72-138 ns.
 */
#pragma once

#include <Eigen/Dense>
#include <Eigen/Geometry>

namespace roislam::geometry
{
/** exp([w]x): the rotation by |w| radians about w; the identity for
 *  |w| <= 1e-12 rad. */
inline Eigen::Matrix3d expSO3(const Eigen::Vector3d& w)
{
  const double angle = w.norm();
  if (!(angle > 1e-12))
    return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
}

/** The rotation vector w with expSO3(w) = R, |w| in [0, pi]. */
inline Eigen::Vector3d logSO3(const Eigen::Matrix3d& R)
{
  const Eigen::AngleAxisd aa(R);
  return aa.axis() * aa.angle();
}

/** The angle of rotation R, radians in [0, pi]. */
inline double rotationAngle(const Eigen::Matrix3d& R)
{
  return Eigen::AngleAxisd(R).angle();
}
}  // namespace roislam::geometry
