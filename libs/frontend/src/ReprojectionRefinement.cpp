#include "ReprojectionRefinement.h"

#include <mrpt/math/geometry.h>

#include <algorithm>
#include <cmath>

namespace roislam::frontend::detail
{
namespace
{
// Projection and its Jacobian w.r.t. the 3-D point.
inline bool project(
    const TPinhole& cam, const Eigen::Vector3d& X, Eigen::Vector2d& u,
    Eigen::Matrix<double, 2, 3>* J)
{
  if (X.z() < 1e-3)
    return false;
  const double iz = 1.0 / X.z();
  u << cam.fx * X.x() * iz + cam.cx, cam.fy * X.y() * iz + cam.cy;
  if (J)
    *J << cam.fx * iz, 0, -cam.fx * X.x() * iz * iz, 0, cam.fy * iz, -cam.fy * X.y() * iz * iz;
  return true;
}

/** d(exp(d) p)/d(d) at d = 0 for the left perturbation: [I, -[p]x]. */
Eigen::Matrix<double, 3, 6> leftJacobian(const Eigen::Vector3d& p)
{
  Eigen::Matrix<double, 3, 6> J;
  J << Eigen::Matrix3d::Identity(), mrpt::math::skew_symmetric3_neg(p).asEigen();
  return J;
}

/** One Huber-weighted reprojection residual r (in sigmas) with Jacobian J. */
void addResidual(
    const Eigen::Vector2d& r, const Eigen::Matrix<double, 2, 6>& J, double huber, Matrix6d& H,
    Vector6d& g, double& sumSq)
{
  const double n = r.norm();
  const double w = n <= huber ? 1.0 : huber / n;
  H.noalias() += w * J.transpose() * J;
  g.noalias() += w * J.transpose() * r;
  sumSq += r.squaredNorm();
}

// One Gauss-Newton system over the given pairs.
void buildSystem(
    const TPinhole& cam, const TCorrespondences& c, const TRigid& T,
    const std::vector<std::size_t>& idx, const TRefineParams& p, Matrix6d& H, Vector6d& g,
    double* sumSq)
{
  const double huber = p.huber;
  H.setZero();
  g.setZero();
  double s = 0;
  const TRigid Tinv = T.inverse();
  for (auto i : idx)
  {
    const double is = 1.0 / (c.sigma.empty() ? p.pixelSigma : c.sigma[i]);
    Eigen::Vector2d u;
    Eigen::Matrix<double, 2, 3> Jp;
    // Forward: b -> a image, X = exp(d) T b.
    const Eigen::Vector3d X = T * c.b[i];
    if (project(cam, X, u, &Jp))
      addResidual((u - c.ua[i]) * is, is * Jp * leftJacobian(X), huber, H, g, s);
    // Backward: a -> b image. Y = T^-1 exp(-d) a => dY/dd = -R^T [I, -[a]x].
    if (project(cam, Tinv * c.a[i], u, &Jp))
      addResidual((u - c.ub[i]) * is, -is * Jp * Tinv.R * leftJacobian(c.a[i]), huber, H, g, s);
  }
  if (sumSq)
    *sumSq = s;
}

TRigid gaussNewton(
    const TPinhole& cam, const TCorrespondences& c, TRigid T, const std::vector<std::size_t>& idx,
    const TRefineParams& p)
{
  Matrix6d H;
  Vector6d g;
  for (int it = 0; it < p.iterations; ++it)
  {
    buildSystem(cam, c, T, idx, p, H, g, nullptr);
    const double lambda = 1e-9 * (H.trace() + 1.0);
    const Vector6d d = -(H + lambda * Matrix6d::Identity()).ldlt().solve(g);
    if (!d.allFinite())
      break;
    T = applyLeft(d, T);
    if (d.norm() < 1e-9)
      break;
  }
  return T;
}

std::vector<std::size_t> selectInliers(
    const TPinhole& cam, const TCorrespondences& c, const TRigid& T, const TRefineParams& p)
{
  std::vector<std::size_t> out;
  const TRigid Tinv = T.inverse();
  const double t2base = p.inlierThresholdPx * p.inlierThresholdPx / (p.pixelSigma * p.pixelSigma);
  const double d2 = p.inlierThreshold3d * p.inlierThreshold3d;
  for (std::size_t i = 0; i < c.size(); ++i)
  {
    const Eigen::Vector3d X = T * c.b[i];
    if ((X - c.a[i]).squaredNorm() > d2)
      continue;
    const double sg = c.sigma.empty() ? p.pixelSigma : c.sigma[i];
    const double t2 = t2base * sg * sg;
    Eigen::Vector2d u1, u2;
    if (!project(cam, X, u1, nullptr) || !project(cam, Tinv * c.a[i], u2, nullptr))
      continue;
    if ((u1 - c.ua[i]).squaredNorm() < t2 && (u2 - c.ub[i]).squaredNorm() < t2)
      out.push_back(i);
  }
  return out;
}
}  // namespace

TRefineResult refineReprojection(
    const TPinhole& cam, const TCorrespondences& c, const TRigid& T0,
    const std::vector<std::size_t>& initialInliers, const TRefineParams& params)
{
  TRefineResult res;
  res.T = T0;
  std::vector<std::size_t> inl = initialInliers;
  for (int round = 0; round < 3; ++round)
  {
    if (inl.size() < 3)
      break;
    const TRigid T = gaussNewton(cam, c, res.T, inl, params);
    auto next = selectInliers(cam, c, T, params);
    if (next.size() < 3)
      break;
    res.T = T;
    const bool same = next == inl;
    inl.swap(next);
    if (same)
      break;
  }
  res.inliers = inl;
  if (inl.empty())
    return res;
  Matrix6d H;
  Vector6d g;
  double sumSq = 0;
  buildSystem(cam, c, res.T, inl, params, H, g, &sumSq);
  res.information = H;
  // sumSq is in sigma units; report pixels at the base sigma.
  res.rmsePx = params.pixelSigma * std::sqrt(sumSq / (2.0 * static_cast<double>(inl.size())));
  double s3 = 0;
  for (auto i : inl)
    s3 += (res.T * c.b[i] - c.a[i]).squaredNorm();
  res.rmse3d = std::sqrt(s3 / static_cast<double>(inl.size()));
  return res;
}
}  // namespace roislam::frontend::detail
