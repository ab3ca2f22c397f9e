#include "RigidMath.h"

#include <mrpt/math/geometry.h>
#include <roislam/geometry/Rotation.h>

namespace roislam::frontend::detail
{
mrpt::poses::CPose3D toPose(const TRigid& T)
{
  // Re-orthonormalise: repeated small updates accumulate rounding.
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(T.R, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d R = svd.matrixU() * svd.matrixV().transpose();
  if (R.determinant() < 0)
    R = -R;
  return mrpt::poses::CPose3D::FromRotationAndTranslation(R, T.t);
}

double rotationAngle(const mrpt::poses::CPose3D& p)
{
  return geometry::rotationAngle(p.getRotationMatrix().asEigen());
}

TRigid applyLeft(const Vector6d& delta, const TRigid& T)
{
  const Eigen::Matrix3d dR = geometry::expSO3(delta.tail<3>());
  TRigid o;
  o.R = dR * T.R;
  o.t = dR * T.t + delta.head<3>();
  return o;
}

Matrix6d tangentInfoToYpr(const Matrix6d& H, const mrpt::poses::CPose3D& T)
{
  // A = d delta / d p, numerically (central differences): T(p + dp) = exp(delta) T(p).
  const double p[6] = {T.x(), T.y(), T.z(), T.yaw(), T.pitch(), T.roll()};
  const TRigid T0 = fromPose(T);
  const TRigid T0inv = T0.inverse();
  Matrix6d A;
  const double eps = 1e-6;
  for (int i = 0; i < 6; ++i)
  {
    Vector6d col;
    for (int sgn = -1; sgn <= 1; sgn += 2)
    {
      double q[6];
      for (int k = 0; k < 6; ++k)
        q[k] = p[k] + (k == i ? sgn * eps : 0.0);
      const TRigid Tq = fromPose(mrpt::poses::CPose3D(q[0], q[1], q[2], q[3], q[4], q[5]));
      // exp(delta) = Tq * T0^-1; for tiny delta: v ~ translation, w ~ rotation vector.
      const Eigen::Matrix3d dR = Tq.R * T0inv.R;
      const Eigen::Vector3d dt = Tq.R * T0inv.t + Tq.t;
      Vector6d d;
      d.head<3>() = dt;
      d.tail<3>() = geometry::logSO3(dR);
      if (sgn < 0)
        col = -d;
      else
        col += d;
    }
    A.col(i) = col / (2 * eps);
  }
  Matrix6d I = A.transpose() * H * A;
  return 0.5 * (I + I.transpose());
}
Matrix6d tangentInfoToPseudoLog(const Matrix6d& H, const TRigid& T)
{
  Matrix6d B = Matrix6d::Zero();
  B.topLeftCorner<3, 3>() = T.R;
  B.topRightCorner<3, 3>() = mrpt::math::skew_symmetric3(T.t).asEigen() * T.R;
  B.bottomRightCorner<3, 3>() = T.R;
  const Matrix6d I = B.transpose() * H * B;
  return 0.5 * (I + I.transpose());
}

Vector6d leftDifference(const TRigid& a, const TRigid& b)
{
  // b = exp(d) a with d = (v, w): Exp(w) = Rb Ra^T, v = tb - Exp(w) ta.
  const Eigen::Matrix3d dR = b.R * a.R.transpose();
  Vector6d d;
  d.head<3>() = b.t - dR * a.t;
  d.tail<3>() = geometry::logSO3(dR);
  return d;
}

std::optional<Matrix6d> covarianceOf(const Matrix6d& information)
{
  const Eigen::LLT<Matrix6d> llt(0.5 * (information + information.transpose()));
  if (llt.info() != Eigen::Success)
    return std::nullopt;
  const Matrix6d C = llt.solve(Matrix6d::Identity());
  if (!C.allFinite())
    return std::nullopt;
  return C;
}

std::optional<Matrix6d> composedInformation(const TRigid& a, const Matrix6d& Ha, const Matrix6d& Hb)
{
  const auto Ca = covarianceOf(Ha);
  const auto Cb = covarianceOf(Hb);
  if (!Ca || !Cb)
    return std::nullopt;
  Matrix6d Ad = Matrix6d::Zero();
  Ad.topLeftCorner<3, 3>() = a.R;
  Ad.topRightCorner<3, 3>() = mrpt::math::skew_symmetric3(a.t).asEigen() * a.R;
  Ad.bottomRightCorner<3, 3>() = a.R;
  return covarianceOf(*Ca + Ad * *Cb * Ad.transpose());
}

TRigid fuseLeft(const TRigid& a, const Matrix6d& Ha, const TRigid& b, const Matrix6d& Hb)
{
  const Vector6d d = leftDifference(a, b);
  const Vector6d f = (Ha + Hb).ldlt().solve(Hb * d);
  if (!f.allFinite())
    return a;
  return applyLeft(f, a);
}
}  // namespace roislam::frontend::detail
