#include "roislam/matching/CRigidTransformRansac.h"

#include <mrpt/config/CConfigFileBase.h>
#include <roislam/common/IniErrors.h>
#include <roislam/geometry/RigidAlignment.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

namespace roislam::matching
{
namespace
{
void check(const CRigidTransformRansac::TOptions& o, const std::string& s)
{
  if (!(o.threshold_m > 0))
    common::throwBadIniKey(s, "threshold_m", "must be > 0");
  if (o.max_iterations < 1)
    common::throwBadIniKey(s, "max_iterations", "must be >= 1");
  if (!(o.confidence > 0 && o.confidence < 1))
    common::throwBadIniKey(s, "confidence", "must be in (0, 1)");
  if (o.min_inliers < 3)
    common::throwBadIniKey(s, "min_inliers", "must be >= 3");
  if (!(o.min_sample_spread >= 0))
    common::throwBadIniKey(s, "min_sample_spread", "must be >= 0");
}

inline Eigen::Vector3d toEigen(const mrpt::math::TPoint3D& p)
{
  return {p.x, p.y, p.z};
}

/** The least-squares motion over the pairs at idx, or nullopt when their
 *  source points are collinear (rotation undetermined). */
std::optional<geometry::TRigid> refit(
    const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b,
    const std::vector<std::size_t>& idx)
{
  const auto [A, B] = geometry::gatherPairs(a, b, idx);
  if (geometry::collinear(B))
    return std::nullopt;
  return geometry::alignRigid(A, B);
}
}  // namespace

void CRigidTransformRansac::TOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& s)
{
  threshold_m = c.read_double(s, "threshold_m", threshold_m);
  max_iterations = c.read_int(s, "max_iterations", max_iterations);
  confidence = c.read_double(s, "confidence", confidence);
  min_inliers = c.read_int(s, "min_inliers", min_inliers);
  const int sd = c.read_int(s, "seed", static_cast<int>(seed));
  if (sd < 0)
    common::throwBadIniKey(s, "seed", "must be >= 0");
  seed = static_cast<std::uint32_t>(sd);
  min_sample_spread = c.read_double(s, "min_sample_spread", min_sample_spread);
  check(*this, s);
}

void CRigidTransformRansac::TOptions::saveToConfigFile(
    mrpt::config::CConfigFileBase& c, const std::string& s) const
{
  c.write(s, "threshold_m", threshold_m);
  c.write(s, "max_iterations", max_iterations);
  c.write(s, "confidence", confidence);
  c.write(s, "min_inliers", min_inliers);
  c.write(s, "seed", static_cast<int>(seed));
  c.write(s, "min_sample_spread", min_sample_spread);
}

CRigidTransformRansac::CRigidTransformRansac() : CRigidTransformRansac(TOptions()) {}

CRigidTransformRansac::CRigidTransformRansac(const TOptions& options) : m_options(options)
{
  check(m_options, "RigidRansac");
}

std::optional<TRigidRansacResult> CRigidTransformRansac::estimate(
    const std::vector<mrpt::math::TPoint3D>& target,
    const std::vector<mrpt::math::TPoint3D>& source) const
{
  if (target.size() != source.size())
    throw std::invalid_argument("CRigidTransformRansac::estimate: target and source sizes differ");
  const std::size_t n = target.size();
  const std::size_t minInliers = static_cast<std::size_t>(m_options.min_inliers);
  if (n < std::max<std::size_t>(3, minInliers))
    return std::nullopt;

  std::vector<Eigen::Vector3d> a(n), b(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    a[i] = toEigen(target[i]);
    b[i] = toEigen(source[i]);
  }
  const double thr = m_options.threshold_m;
  const double thr2 = thr * thr;
  const double minSpread = m_options.min_sample_spread * thr;

  auto countInliers = [&](const geometry::TRigid& T, std::vector<std::size_t>* out, double* sumSq)
  {
    std::size_t c = 0;
    double s = 0;
    for (std::size_t i = 0; i < n; ++i)
    {
      const double d2 = (T.R * b[i] + T.t - a[i]).squaredNorm();
      if (d2 < thr2)
      {
        ++c;
        s += d2;
        if (out)
          out->push_back(i);
      }
    }
    if (sumSq)
      *sumSq = s;
    return c;
  };

  std::mt19937 rng(m_options.seed);
  std::uniform_int_distribution<std::size_t> pick(0, n - 1);
  std::size_t bestCount = 0;
  double bestSumSq = std::numeric_limits<double>::max();
  geometry::TRigid best;
  int needed = m_options.max_iterations;
  int it = 0;
  const double logFail = std::log(1.0 - m_options.confidence);
  for (; it < needed && it < m_options.max_iterations; ++it)
  {
    std::size_t s[3];
    s[0] = pick(rng);
    do
      s[1] = pick(rng);
    while (s[1] == s[0]);
    do
      s[2] = pick(rng);
    while (s[2] == s[0] || s[2] == s[1]);
    // Cheap rejection: a rigid motion preserves pairwise distances.
    bool consistent = true;
    for (int p = 0; p < 3 && consistent; ++p)
    {
      const int q = (p + 1) % 3;
      const double da = (a[s[p]] - a[s[q]]).norm(), db = (b[s[p]] - b[s[q]]).norm();
      if (std::abs(da - db) > 2 * thr || db < minSpread)
        consistent = false;
    }
    if (!consistent)
      continue;
    Eigen::Matrix3d A, B;
    for (int k = 0; k < 3; ++k)
    {
      A.col(k) = a[s[k]];
      B.col(k) = b[s[k]];
    }
    if (geometry::collinear(B))
      continue;
    const geometry::TRigid T = geometry::alignRigid(A, B);
    double sumSq = 0;
    const std::size_t c = countInliers(T, nullptr, &sumSq);
    if (c > bestCount || (c == bestCount && sumSq < bestSumSq))
    {
      bestCount = c;
      bestSumSq = sumSq;
      best = T;
      // Adaptive stop: iterations for `confidence` of one all-inlier sample.
      const double w = static_cast<double>(c) / static_cast<double>(n);
      const double pGood = w * w * w;
      if (pGood >= 1.0)
        needed = it + 1;
      else if (pGood > 0)
        needed = static_cast<int>(
            std::min<double>(m_options.max_iterations, std::ceil(logFail / std::log(1.0 - pGood))));
    }
  }
  if (bestCount < std::max<std::size_t>(3, minInliers))
    return std::nullopt;

  // Least-squares refit on the inliers, repeated while the inlier set grows.
  TRigidRansacResult res;
  geometry::TRigid T = best;
  std::vector<std::size_t> inl;
  countInliers(T, &inl, nullptr);
  for (int round = 0; round < 3; ++round)
  {
    const auto next = refit(a, b, inl);
    if (!next)
      break;
    std::vector<std::size_t> inl2;
    countInliers(*next, &inl2, nullptr);
    if (inl2.size() < inl.size())
      break;
    T = *next;
    const bool same = inl2 == inl;
    inl.swap(inl2);
    if (same)
      break;
  }
  if (inl.size() < std::max<std::size_t>(3, minInliers))
    return std::nullopt;
  double sumSq = 0;
  for (auto i : inl)
    sumSq += (T.R * b[i] + T.t - a[i]).squaredNorm();
  res.transform = T.toPose();
  res.inliers = std::move(inl);
  res.rmse = std::sqrt(sumSq / static_cast<double>(res.inliers.size()));
  res.iterations = it;
  return res;
}
}  // namespace roislam::matching
