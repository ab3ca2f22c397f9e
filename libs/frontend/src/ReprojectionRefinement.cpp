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
    Vector6d& g)
{
  const double n = r.norm();
  const double w = n <= huber ? 1.0 : huber / n;
  H.noalias() += w * J.transpose() * J;
  g.noalias() += w * J.transpose() * r;
}

// One Gauss-Newton system over the given pairs.
void buildSystem(
    const TPinhole& cam, const TCorrespondences& c, const TRigid& T,
    const std::vector<std::size_t>& idx, const TRefineParams& p, Matrix6d& H, Vector6d& g)
{
  const double huber = p.huber;
  H.setZero();
  g.setZero();
  const TRigid Tinv = T.inverse();
  for (auto i : idx)
  {
    const double is = 1.0 / (c.sigma.empty() ? p.pixelSigma : c.sigma[i]);
    Eigen::Vector2d u;
    Eigen::Matrix<double, 2, 3> Jp;
    // Forward: b -> a image, X = exp(d) T b.
    const Eigen::Vector3d X = T * c.b[i];
    if (project(cam, X, u, &Jp))
      addResidual((u - c.ua[i]) * is, is * Jp * leftJacobian(X), huber, H, g);
    // Backward: a -> b image. Y = T^-1 exp(-d) a => dY/dd = -R^T [I, -[a]x].
    if (project(cam, Tinv * c.a[i], u, &Jp))
      addResidual((u - c.ub[i]) * is, -is * Jp * Tinv.R * leftJacobian(c.a[i]), huber, H, g);
  }
}

TRigid gaussNewton(
    const TPinhole& cam, const TCorrespondences& c, TRigid T, const std::vector<std::size_t>& idx,
    const TRefineParams& p)
{
  Matrix6d H;
  Vector6d g;
  for (int it = 0; it < p.iterations; ++it)
  {
    buildSystem(cam, c, T, idx, p, H, g);
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
/** How a residual moves with the pixel its 3-D point X was lifted from
 *  (depth held): the lift X = z K^-1 u, rotated by R, reprojected by Jp. */
Eigen::Matrix2d liftedPixelJacobian(
    const TPinhole& cam, const Eigen::Matrix<double, 2, 3>& Jp, const Eigen::Matrix3d& R,
    const Eigen::Vector3d& X)
{
  Eigen::Matrix<double, 3, 2> G = Eigen::Matrix<double, 3, 2>::Zero();
  G(0, 0) = X.z() / cam.fx;
  G(1, 1) = X.z() / cam.fy;
  return Jp * R * G;
}

/** One direction's residual covariance (px^2): the pixel noise of the
 *  keypoint it is compared with and of the one it was lifted from (carried
 *  through the reprojection by A, liftedPixelJacobian), and the lifted
 *  point's axial depth noise (carried by d, the reprojection's change per
 *  unit of depth along the ray). */
Eigen::Matrix2d residualCovariance(
    const Eigen::Matrix2d& A, const Eigen::Vector2d& d, double sigmaPx, double sigmaZ)
{
  // Both directions see the same keypoints: their pixel noise counts twice
  // over the pair's two residuals, so each carries it doubled; the depth
  // noise of a and of b are separate readings.
  return 2 * sigmaPx * sigmaPx * (Eigen::Matrix2d::Identity() + A * A.transpose()) +
         sigmaZ * sigmaZ * d * d.transpose();
}

/** The RMS reprojection error in pixels over both directions of the pairs
 *  (unweighted, whatever each pair's sigma). */
double pixelRms(
    const TPinhole& cam, const TCorrespondences& c, const TRigid& T,
    const std::vector<std::size_t>& idx)
{
  const TRigid Tinv = T.inverse();
  double sum = 0;
  std::size_t n = 0;
  Eigen::Vector2d u;
  for (auto i : idx)
  {
    if (project(cam, T * c.b[i], u, nullptr))
    {
      sum += (u - c.ua[i]).squaredNorm();
      ++n;
    }
    if (project(cam, Tinv * c.a[i], u, nullptr))
    {
      sum += (u - c.ub[i]).squaredNorm();
      ++n;
    }
  }
  return n ? std::sqrt(sum / (2.0 * static_cast<double>(n))) : 0.0;
}

Matrix6d estimatorInformation(
    const TPinhole& cam, const TCorrespondences& c, const TRigid& T,
    const std::vector<std::size_t>& idx, const TRefineParams& p)
{
  Matrix6d H = Matrix6d::Zero();
  // How the weighted normal equations' right-hand side moves with a shift
  // common to all keypoints of image a (Ka) and of image b (Kb); only for a
  // camera that has one.
  const bool common = p.commonPixelSigma > 0;
  Eigen::Matrix<double, 6, 2> Ka = Eigen::Matrix<double, 6, 2>::Zero();
  Eigen::Matrix<double, 6, 2> Kb = Eigen::Matrix<double, 6, 2>::Zero();
  double chi2 = 0;
  std::size_t n = 0;
  const auto sz = [&p](double z) { return p.depthSigma ? p.depthSigma(z) : 0.0; };
  // One direction: residual r (Jacobian J) of the point `lifted` from one
  // image, rotated by R and reprojected (Jp) into the other, against that
  // image's keypoint. A shift of the compared image moves r by -delta, one
  // of the lifting image by A delta.
  const auto addDirection = [&](const Eigen::Matrix<double, 2, 3>& Jp, const Eigen::Matrix3d& R,
                                const Eigen::Vector3d& lifted, const Eigen::Matrix<double, 2, 6>& J,
                                const Eigen::Vector2d& r, double sigmaPx,
                                Eigen::Matrix<double, 6, 2>& kCompared,
                                Eigen::Matrix<double, 6, 2>& kLifting)
  {
    const Eigen::Matrix2d A = liftedPixelJacobian(cam, Jp, R, lifted);
    const Eigen::Matrix2d W =
        residualCovariance(A, Jp * R * (lifted / lifted.z()), sigmaPx, sz(lifted.z())).inverse();
    H.noalias() += J.transpose() * W * J;
    if (common)
    {
      kCompared.noalias() -= J.transpose() * W;
      kLifting.noalias() += J.transpose() * W * A;
    }
    chi2 += r.dot(W * r);
    n += 2;
  };
  const TRigid Tinv = T.inverse();
  for (auto i : idx)
  {
    const double s = c.sigma.empty() ? p.pixelSigma : c.sigma[i];
    Eigen::Vector2d u;
    Eigen::Matrix<double, 2, 3> Jp;
    // Forward: b lifted, compared in a.
    const Eigen::Vector3d X = T * c.b[i];
    if (project(cam, X, u, &Jp))
      addDirection(Jp, T.R, c.b[i], Jp * leftJacobian(X), u - c.ua[i], s, Ka, Kb);
    // Backward: a lifted, compared in b.
    if (project(cam, Tinv * c.a[i], u, &Jp))
      addDirection(Jp, Tinv.R, c.a[i], -Jp * Tinv.R * leftJacobian(c.a[i]), u - c.ub[i], s, Kb, Ka);
  }
  // The variance factor (chi2 per degree of freedom; each pair's two
  // directions count once, their chi2 is already halved by the doubled pixel
  // noise) corrects the assumed noise by the fit's own.
  const double dof = 0.5 * static_cast<double>(n) - 6.0;
  // Never below 1: the inlier gates truncate the residuals, so their spread
  // reads low (unclamped, the edges of the global-shutter test loop read
  // chi2 median 12.7 instead of 2.9).
  const double factor = dof > 0 ? std::max(1.0, chi2 / dof) : 1.0;
  if (!common)
    return H / factor;
  // A shift common to all of an image's keypoints moves the estimate by
  // -H^-1 K delta whatever the keypoint count: its covariance adds to the
  // per-keypoint part instead of averaging down with it.
  const Eigen::LDLT<Matrix6d> ldlt(H);
  if (ldlt.info() != Eigen::Success)
    return H / factor;
  const Eigen::Matrix<double, 6, 2> Ma = ldlt.solve(Ka);
  const Eigen::Matrix<double, 6, 2> Mb = ldlt.solve(Kb);
  const double s2 = p.commonPixelSigma * p.commonPixelSigma;
  const Matrix6d cov =
      factor * ldlt.solve(Matrix6d::Identity()) + s2 * (Ma * Ma.transpose() + Mb * Mb.transpose());
  const Matrix6d info = cov.inverse();
  return info.allFinite() ? Matrix6d(0.5 * (info + info.transpose())) : Matrix6d(H / factor);
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
  buildSystem(cam, c, res.T, inl, params, H, g);
  res.information = H;
  res.edgeInformation = estimatorInformation(cam, c, res.T, inl, params);
  res.rmsePx = pixelRms(cam, c, res.T, inl);
  double s3 = 0;
  for (auto i : inl)
    s3 += (res.T * c.b[i] - c.a[i]).squaredNorm();
  res.rmse3d = std::sqrt(s3 / static_cast<double>(inl.size()));
  return res;
}
}  // namespace roislam::frontend::detail
