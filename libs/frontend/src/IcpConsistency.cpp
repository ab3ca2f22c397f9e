#include "IcpConsistency.h"

#include <roislam/common/Median.h>
#include <roislam/frontend/PoseUncertainty.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
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
  m_samples.push_back({d, featureCov, icpCov, std::isfinite(share) ? share : 0.0, pairShare});
  while (m_samples.size() > m_window)
    m_samples.pop_front();
  update();
}

void CIcpConsistency::reset()
{
  m_samples.clear();
  m_scale.reset();
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

void CIcpConsistency::update()
{
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
