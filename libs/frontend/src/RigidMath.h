/* Private helpers of the front end: rigid transforms (geometry::TRigid), the
 * left-perturbation update used by every Gauss-Newton solver here, and the
 * conversion of an information matrix from that tangent space to MRPT's
 * CPose3DPDFGaussianInf convention (x, y, z, yaw, pitch, roll).
 */
#pragma once

#include <mrpt/poses/CPose3D.h>
#include <roislam/geometry/TRigid.h>

#include <Eigen/Dense>
#include <optional>

namespace roislam::frontend::detail
{
using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

using geometry::TRigid;

inline TRigid fromPose(const mrpt::poses::CPose3D& p)
{
  return TRigid::fromPose(p);
}
/** Rotation angle of a pose, radians. */
double rotationAngle(const mrpt::poses::CPose3D& p);
/** T as a pose, its rotation re-orthonormalised (repeated small updates
 *  accumulate rounding). */
mrpt::poses::CPose3D toPose(const TRigid& T);

/** exp(delta) * T with delta = (v, w): x' = Exp(w) (R x + t) + v, whose
 *  derivative at delta = 0 is [I, -[x']_x]. */
TRigid applyLeft(const Vector6d& delta, const TRigid& T);

/** Information-weighted mean of two estimates of one motion, in the left
 *  perturbation around `a`: delta = (Ha + Hb)^-1 Hb log(b a^-1). */
TRigid fuseLeft(const TRigid& a, const Matrix6d& Ha, const TRigid& b, const Matrix6d& Hb);

/** log(b a^-1) as the left perturbation d with b = exp(d) a (applyLeft). */
Vector6d leftDifference(const TRigid& a, const TRigid& b);

/** The covariance of an information matrix; nullopt when it is not positive
 *  definite (an undetermined direction). */
std::optional<Matrix6d> covarianceOf(const Matrix6d& information);

/** The information of a * b (left perturbation, as in applyLeft) from a's
 *  and b's, independent: b's perturbation moves into a's reference frame by
 *  a's adjoint, Cov = Cov_a + Ad(a) Cov_b Ad(a)^T with Ad(a) = [R, [t]x R;
 *  0, R]. nullopt when either leaves a direction undetermined. */
std::optional<Matrix6d> composedInformation(
    const TRigid& a, const Matrix6d& Ha, const Matrix6d& Hb);

/** Information H of delta (left perturbation of T, as in applyLeft) ->
 *  information of (x, y, z, yaw, pitch, roll) of T (CPose3DPDFGaussianInf). */
Matrix6d tangentInfoToYpr(const Matrix6d& H, const mrpt::poses::CPose3D& T);

/** Information H of delta (left perturbation of T) -> information of the
 *  SE(3) pseudo-log e = [x y z rx ry rz] of the right perturbation T exp(e),
 *  the residual MRPT's SPA weighs (d = [R, [t]x R; 0, R] e). */
Matrix6d tangentInfoToPseudoLog(const Matrix6d& H, const TRigid& T);
}  // namespace roislam::frontend::detail
