#include "IcpConsistency.h"

#include <roislam/common/Median.h>
#include <roislam/frontend/PoseUncertainty.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

namespace roislam::frontend::detail
{
bool icpBetterDetermined(const TInformation66& icp, double icpScale, const TInformation66& other)
{
  const auto si = worstSigmas(icp);
  if (!si || !(icpScale > 0) || !std::isfinite(icpScale))
    return false;
  const auto so = worstSigmas(other);
  return !so || std::sqrt(icpScale) * si->translation_m < so->translation_m;
}

CIcpConsistency::CIcpConsistency(std::size_t window, std::size_t minSamples, double minScale)
    : m_window(window), m_minSamples(minSamples), m_minScale(minScale)
{
  if (window == 0 || minSamples == 0 || minSamples > window)
    throw std::invalid_argument("CIcpConsistency: need 0 < minSamples <= window");
  if (!(minScale > 0 && minScale <= 1))
    throw std::invalid_argument("CIcpConsistency: need 0 < minScale <= 1");
}

double CIcpConsistency::shareScale(double k, double pairShare)
{
  return k < 1 ? k : pairShare * (k - 1) + 1;
}

void CIcpConsistency::add(
    const Vector6d& d, const Matrix6d& featureCov, const Matrix6d& icpCov, double pairShare)
{
  if (!(pairShare > 0 && pairShare <= 1))
    throw std::invalid_argument("CIcpConsistency::add: pairShare must be in (0, 1]");
  if (!d.allFinite() || !featureCov.allFinite() || !icpCov.allFinite())
    return;
  const Eigen::LDLT<Matrix6d> icpLdlt(icpCov);
  const double share = (featureCov * icpLdlt.solve(Matrix6d::Identity())).trace() / 6 / pairShare;
  TSample sample;
  sample.d = d;
  sample.featureCov = featureCov;
  sample.icpCov = icpCov;
  sample.pairShare = pairShare;
  sample.share = std::isfinite(share) ? share : 0.0;
  m_samples.push_back(std::move(sample));
  while (m_samples.size() > m_window)
    m_samples.pop_front();
  update();
}

void CIcpConsistency::reset()
{
  m_samples.clear();
  m_scale.reset();
  m_joint.reset();
  m_share = 0;
}

std::optional<double> CIcpConsistency::scaleFor(double pairShare) const
{
  if (!m_scale)
    return std::nullopt;
  return shareScale(*m_scale, pairShare);
}

double CIcpConsistency::informationKept(double pairShare) const
{
  if (!m_scale || !std::isfinite(*m_scale) || *m_scale <= 1)
    return pairShare;
  return *m_scale / (*m_scale - 1 + 1 / pairShare);
}

double CIcpConsistency::chi2(
    const Vector6d& d, const Matrix6d& featureCov, const Matrix6d& icpCov, double k)
{
  const Eigen::LDLT<Matrix6d> ldlt(featureCov + k * icpCov);
  const double v = d.dot(ldlt.solve(d));
  return ldlt.info() == Eigen::Success && std::isfinite(v)
             ? std::max(0.0, v)
             : std::numeric_limits<double>::infinity();
}

double CIcpConsistency::medianChi2(double k) const
{
  std::vector<double> c;
  c.reserve(m_samples.size());
  for (const auto& s : m_samples)
    c.push_back(chi2(s.d, s.featureCov, s.icpCov, shareScale(k, s.pairShare)));
  return common::upperMedian(std::move(c));
}

std::optional<CIcpConsistency::TJointScales> CIcpConsistency::fitJointScales(
    const std::vector<TComparison>& samples, const std::optional<TJointScales>& start)
{
  if (samples.size() < 2)
    return std::nullopt;
  // Negative log-likelihood of the disagreements under N(0, a Sf + b Si),
  // Student-t with nu = 4 in the Mahalanobis distance (robust to the odd
  // wrong match), over (log a, log b).
  constexpr double kNu = 4, kLogSpan = 7, kGridStep = 1;
  const auto nll = [&samples](double la, double lb)
  {
    // Bounded: where one estimator explains every disagreement the other's
    // scale falls without end, and the search must stop.
    if (std::abs(la) > kLogSpan || std::abs(lb) > kLogSpan)
      return std::numeric_limits<double>::infinity();
    const double a = std::exp(la), b = std::exp(lb);
    double sum = 0;
    for (const auto& s : samples)
    {
      const Eigen::LLT<Matrix6d> llt(a * s.featureCov + shareScale(b, s.pairShare) * s.icpCov);
      if (llt.info() != Eigen::Success)
        return std::numeric_limits<double>::infinity();
      const Vector6d z = llt.matrixL().solve(s.d);
      sum += 0.5 * (kNu + 6) * std::log1p(z.squaredNorm() / kNu) +
             llt.matrixLLT().diagonal().array().log().sum();
    }
    return std::isfinite(sum) ? sum : std::numeric_limits<double>::infinity();
  };
  constexpr double kGaussianScatter = 0.8167;  // below
  // A coarse grid over three decades each way, then a pattern search down
  // to 1e-3 in log scale (0.1 %). From the previous fit (a window that
  // moved by one comparison) the search alone, in finer first steps.
  double bestLa = 0, bestLb = 0, best = std::numeric_limits<double>::infinity();
  double step = kGridStep / 8;
  if (start && start->features > 0 && start->icp > 0)
  {
    bestLa = std::log(start->features * kGaussianScatter);
    bestLb = std::log(start->icp * kGaussianScatter);
    best = nll(bestLa, bestLb);
  }
  if (!std::isfinite(best))
  {
    for (double la = -kLogSpan; la <= kLogSpan; la += kGridStep)
      for (double lb = -kLogSpan; lb <= kLogSpan; lb += kGridStep)
        if (const double v = nll(la, lb); v < best)
          std::tie(best, bestLa, bestLb) = std::make_tuple(v, la, lb);
    step = kGridStep / 2;
  }
  if (!std::isfinite(best))
    return std::nullopt;
  while (step > 1e-3)
  {
    bool improved = false;
    for (const auto& [da, db] : {std::pair{step, 0.0}, {-step, 0.0}, {0.0, step}, {0.0, -step}})
      if (const double v = nll(bestLa + da, bestLb + db); v < best)
      {
        std::tie(best, bestLa, bestLb) = std::make_tuple(v, bestLa + da, bestLb + db);
        improved = true;
      }
    if (!improved)
      step /= 2;
  }
  // The Student-t's scatter is not the covariance: on Gaussian
  // disagreements its fit reads c = 0.8167 times it (kGaussianScatter), the
  // c that solves E[(nu + 6) u / (nu + u)] = 6 for u = q / c, q ~ chi2(6).
  return TJointScales{std::exp(bestLa) / kGaussianScatter, std::exp(bestLb) / kGaussianScatter};
}

void CIcpConsistency::update()
{
  const auto previous = m_joint;
  m_joint.reset();
  if (m_samples.size() >= m_window)
  {
    m_joint =
        fitJointScales(std::vector<TComparison>(m_samples.begin(), m_samples.end()), previous);
  }
  std::vector<double> s;
  s.reserve(m_samples.size());
  for (const auto& x : m_samples)
    s.push_back(x.share);
  m_share = common::upperMedian(std::move(s));
  m_scale.reset();
  if (m_samples.size() < m_minSamples)
    return;
  // Every sample's chi-square falls as k grows, so their median does too:
  // bisection on log k (to 1e-3 relative).
  if (medianChi2(m_minScale) <= kChi2Median6)
  {
    m_scale = m_minScale;
    return;
  }
  if (medianChi2(kMaxScale) > kChi2Median6)
  {
    m_scale = std::numeric_limits<double>::infinity();
    return;
  }
  double lo = std::log(m_minScale), hi = std::log(kMaxScale);
  while (hi - lo > 1e-3)
  {
    const double mid = 0.5 * (lo + hi);
    (medianChi2(std::exp(mid)) > kChi2Median6 ? lo : hi) = mid;
  }
  m_scale = std::exp(hi);
}
}  // namespace roislam::frontend::detail
