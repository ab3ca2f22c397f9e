#include "CDepthIcp.h"

#include <roislam/geometry/Rotation.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace roislam::frontend::detail
{
namespace
{
const float kNaN = std::numeric_limits<float>::quiet_NaN();
// Gauss-Newton's first iterations capture: a wide gate, a quarter of the
// pairs, and no convergence test before the first tight-gate iteration.
const int kCaptureIterations = 3;

// Plausibility: ICP should only correct the prediction, not jump.
bool plausible(const TRigid& T, const TRigid& guess)
{
  const TRigid dT = {T.R * guess.R.transpose(), T.t - T.R * guess.R.transpose() * guess.t};
  const double ang = geometry::rotationAngle(dT.R);
  return !((T.t - guess.t).norm() > 0.3 || ang > 0.5);
}

/** The information ICP claims for its pose, from the normal equations (H,
 *  pairs, sum of squared residuals): kIndependentPairShare of the pairs,
 *  with a 3 mm floor on the residual sigma. */
Matrix6d modelledInformation(const Matrix6d& H, std::size_t pairs, double sumSq)
{
  const double sigma = std::max(std::sqrt(sumSq / static_cast<double>(pairs)), 0.003);
  return H / (sigma * sigma) * CDepthIcp::kIndependentPairShare;
}

/** The result at T from the normal equations (H, pairs, sum of squared
 *  residuals) built there. */
CDepthIcp::TResult makeResult(const TRigid& T, const Matrix6d& H, std::size_t pairs, double sumSq)
{
  CDepthIcp::TResult out;
  out.T = T;
  out.pairs = pairs;
  out.rmse = std::sqrt(sumSq / static_cast<double>(pairs));
  out.information = modelledInformation(H, pairs, sumSq);
  out.edgeInformation = H / (out.rmse * out.rmse + 1e-12) * CDepthIcp::kIndependentPairShare;
  return out;
}
}  // namespace

CDepthIcp::CDepthIcp(const TParams& params, const mrpt::img::TCamera& cam) : m_params(params)
{
  if (m_params.decimation < 1)
    throw std::invalid_argument("CDepthIcp: decimation must be >= 1");
  const int d = m_params.decimation;
  const int W = static_cast<int>(cam.ncols), Hh = static_cast<int>(cam.nrows);
  m_cols = W / d;
  m_rows = Hh / d;
  m_fx = cam.fx() / d;
  m_fy = cam.fy() / d;
  m_cx = cam.cx() / d;
  m_cy = cam.cy() / d;
  const double k1 = cam.dist[0], k2 = cam.dist[1], p1 = cam.dist[2], p2 = cam.dist[3],
               k3 = cam.dist[4];
  m_srcIndex.assign(static_cast<std::size_t>(m_cols * m_rows), -1);
  m_rays.resize(m_srcIndex.size());
  // Cell (r, c) is the undistorted full-resolution pixel (c*d, r*d); its depth
  // is sampled where the lens put it (plumb-bob model, nearest pixel).
  for (int r = 0; r < m_rows; ++r)
    for (int c = 0; c < m_cols; ++c)
    {
      const double x = (c * d - cam.cx()) / cam.fx(), y = (r * d - cam.cy()) / cam.fy();
      const double r2 = x * x + y * y;
      const double radial = 1 + k1 * r2 + k2 * r2 * r2 + k3 * r2 * r2 * r2;
      const double xd = x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x);
      const double yd = y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y;
      const int u = static_cast<int>(std::lround(xd * cam.fx() + cam.cx()));
      const int v = static_cast<int>(std::lround(yd * cam.fy() + cam.cy()));
      const std::size_t k = static_cast<std::size_t>(r * m_cols + c);
      m_rays[k] = Eigen::Vector3f(static_cast<float>(x), static_cast<float>(y), 1.f);
      if (u >= 0 && v >= 0 && u < W && v < Hh)
        m_srcIndex[k] = v * W + u;
    }
}

CDepthIcp::TMap CDepthIcp::buildMap(const cv::Mat& depth) const
{
  if (depth.type() != CV_32FC1 || !depth.isContinuous())
    throw std::invalid_argument("CDepthIcp::buildMap: expected continuous CV_32FC1 depth");
  TMap m;
  m.cols = m_cols;
  m.rows = m_rows;
  const std::size_t n = m_srcIndex.size();
  m.points.assign(n, Eigen::Vector3f(kNaN, kNaN, kNaN));
  m.normals.assign(n, Eigen::Vector3f(kNaN, kNaN, kNaN));
  const float* D = depth.ptr<float>();
  const float zmin = static_cast<float>(m_params.minDepth),
              zmax = static_cast<float>(m_params.maxDepth);
  for (std::size_t k = 0; k < n; ++k)
  {
    if (m_srcIndex[k] < 0)
      continue;
    const float z = D[m_srcIndex[k]];
    if (z >= zmin && z <= zmax)
      m.points[k] = m_rays[k] * z;
  }
  // Normals from central differences; skip depth discontinuities.
  for (int r = 1; r + 1 < m_rows; ++r)
    for (int c = 1; c + 1 < m_cols; ++c)
    {
      const std::size_t k = static_cast<std::size_t>(r * m_cols + c);
      const Eigen::Vector3f& p = m.points[k];
      if (!std::isfinite(p.z()))
        continue;
      const Eigen::Vector3f& l = m.points[k - 1];
      const Eigen::Vector3f& rr = m.points[k + 1];
      const Eigen::Vector3f& u = m.points[k - static_cast<std::size_t>(m_cols)];
      const Eigen::Vector3f& dn = m.points[k + static_cast<std::size_t>(m_cols)];
      if (!std::isfinite(l.z()) || !std::isfinite(rr.z()) || !std::isfinite(u.z()) ||
          !std::isfinite(dn.z()))
        continue;
      const float jump = 0.05f * p.z() * static_cast<float>(m_params.decimation);
      if (std::abs(l.z() - rr.z()) > jump || std::abs(u.z() - dn.z()) > jump)
        continue;
      Eigen::Vector3f nrm = (rr - l).cross(dn - u);
      const float len = nrm.norm();
      if (!(len > 0))
        continue;
      nrm /= len;
      if (nrm.dot(p) > 0)
        nrm = -nrm;
      m.normals[k] = nrm;
    }
  return m;
}

CDepthIcp::TNormalEquations CDepthIcp::normalEquations(
    const TMap& ref, const TMap& cur, const TRigid& T, double gate, int stride) const
{
  const double huber = 0.01;
  TNormalEquations eq;
  eq.H.setZero();
  eq.g.setZero();
  const Eigen::Matrix3f R = T.R.cast<float>();
  const Eigen::Vector3f t = T.t.cast<float>();
  const float gate2 = static_cast<float>(gate * gate);
  double h[21] = {}, g[6] = {}, sumSq = 0;
  std::size_t pairs = 0;
  const float fx = static_cast<float>(m_fx), fy = static_cast<float>(m_fy),
              cx = static_cast<float>(m_cx), cy = static_cast<float>(m_cy);
  for (int row = 0; row < m_rows; row += stride)
    for (int col = 0; col < m_cols; col += stride)
    {
      const Eigen::Vector3f& p = cur.points[static_cast<std::size_t>(row * m_cols + col)];
      if (!std::isfinite(p.z()))
        continue;
      const Eigen::Vector3f q = R * p + t;
      if (q.z() < 1e-3f)
        continue;
      // Nearest cell, in float with one division; rounded inline
      // (std::lround is a library call, and this loop runs for every pixel
      // of every iteration).
      const float iz = 1.f / q.z();
      const float u = fx * q.x() * iz + cx, v = fy * q.y() * iz + cy;
      if (!(u > -0.5f && v > -0.5f))
        continue;
      const int c = static_cast<int>(u + 0.5f), r = static_cast<int>(v + 0.5f);
      if (c >= m_cols || r >= m_rows)
        continue;
      const std::size_t j = static_cast<std::size_t>(r * m_cols + c);
      const Eigen::Vector3f& nv = ref.normals[j];
      if (!std::isfinite(nv.z()))
        continue;
      const Eigen::Vector3f diff = q - ref.points[j];
      if (diff.squaredNorm() > gate2)
        continue;
      const double res = nv.dot(diff);
      const double w = std::abs(res) <= huber ? 1.0 : huber / std::abs(res);
      const Eigen::Vector3f qxn = q.cross(nv);
      const double J[6] = {nv.x(), nv.y(), nv.z(), qxn.x(), qxn.y(), qxn.z()};
      // The upper triangle only (H is symmetric; mirrored below), summed in
      // locals the compiler can keep in registers.
      for (int a = 0, e = 0; a < 6; ++a)
      {
        const double wJa = w * J[a];
        for (int b = a; b < 6; ++b, ++e)
          h[e] += wJa * J[b];
        g[a] += wJa * res;
      }
      sumSq += res * res;
      ++pairs;
    }
  for (int a = 0, e = 0; a < 6; ++a)
  {
    for (int b = a; b < 6; ++b, ++e)
      eq.H(a, b) = eq.H(b, a) = h[e];
    eq.g[a] = g[a];
  }
  eq.sumSq = sumSq;
  eq.pairs = pairs;
  return eq;
}

std::optional<TRigid> CDepthIcp::gaussNewton(
    const TMap& ref, const TMap& cur, const TRigid& guess, int pairStride, int* iterations,
    std::optional<TNormalEquations>* converged) const
{
  TRigid T = guess;
  converged->reset();
  for (int it = 0; it < m_params.maxIterations; ++it)
  {
    *iterations = it + 1;
    // Shrinking gate: wide at first to capture, tight later to reject outliers.
    // The wide-gate iterations only capture: every other cell of every
    // other row of the current frame is enough for them (a quarter of the
    // work), the tight-gate ones use every pairStride-th cell.
    const bool capture = it < kCaptureIterations;
    const double gate = capture ? m_params.maxDistance : 0.5 * m_params.maxDistance;
    const int stride = capture ? 2 * pairStride : pairStride;
    TNormalEquations eq = normalEquations(ref, cur, T, gate, stride);
    if (eq.pairs * static_cast<std::size_t>(stride * stride) <
        static_cast<std::size_t>(m_params.minPairs))
      return std::nullopt;
    // Damping keeps unobservable directions at the guess.
    const double lambda = 1e-4 * eq.H.trace() / 6.0 + 1e-9;
    const Vector6d d = -(eq.H + lambda * Matrix6d::Identity()).ldlt().solve(eq.g);
    if (!d.allFinite())
      return std::nullopt;
    T = applyLeft(d, T);
    // Converged once a step moves the pose by less than convergedStepSigma
    // of the standard deviation ICP itself claims (Mahalanobis norm under
    // its modelled information): projective association keeps re-pairing
    // cells, so the steps rarely reach the absolute floor (fr1/rpy: 48 of 90
    // alignments ran all 15 iterations, their last steps 10-300 um) and the
    // further iterations only move the pose within its noise. Not before
    // one iteration with the tight gate has run.
    const double stop = m_params.convergedStepSigma;
    const bool floor = d.head<3>().norm() < 1e-5 && d.tail<3>().norm() < 1e-5;
    if (floor ||
        (!capture && d.dot(modelledInformation(eq.H, eq.pairs, eq.sumSq) * d) < stop * stop))
    {
      // The last tight-gate equations, built a step within the pose's noise
      // from T, describe T as well as new ones would (which would cost one
      // more pass over every cell, about a sixth of an alignment).
      if (!capture)
        *converged = std::move(eq);
      break;
    }
  }
  return T;
}

std::optional<CDepthIcp::TResult> CDepthIcp::align(
    const TMap& ref, const TMap& cur, const TRigid& guess, int pairStride) const
{
  if (ref.cols != m_cols || cur.cols != m_cols || ref.rows != m_rows || cur.rows != m_rows)
    throw std::invalid_argument("CDepthIcp::align: maps of a different camera");
  if (pairStride < 1)
    throw std::invalid_argument("CDepthIcp::align: pairStride must be >= 1");
  int iterations = 0;
  std::optional<TNormalEquations> converged;
  const double tightGate = 0.5 * m_params.maxDistance;
  const std::optional<TRigid> T = gaussNewton(ref, cur, guess, pairStride, &iterations, &converged);
  if (!T)
    return std::nullopt;
  const TNormalEquations eq =
      converged ? *converged : normalEquations(ref, cur, *T, tightGate, pairStride);
  // minPairs counts the pairs all cells would give.
  if (eq.pairs * static_cast<std::size_t>(pairStride * pairStride) <
      static_cast<std::size_t>(m_params.minPairs))
    return std::nullopt;
  if (!plausible(*T, guess))
    return std::nullopt;
  CDepthIcp::TResult out = makeResult(*T, eq.H, eq.pairs, eq.sumSq);
  out.iterations = iterations;
  return out;
}
}  // namespace roislam::frontend::detail
