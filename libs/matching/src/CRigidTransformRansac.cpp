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

namespace
{
/** The point pairs (a = target, b = source) and the inlier threshold. */
class CRansacPairs
{
 public:
  CRansacPairs(
      const std::vector<mrpt::math::TPoint3D>& target,
      const std::vector<mrpt::math::TPoint3D>& source, double threshold)
      : m_thr(threshold), m_thr2(threshold * threshold)
  {
    for (std::size_t i = 0; i < target.size(); ++i)
    {
      m_a.push_back(toEigen(target[i]));
      m_b.push_back(toEigen(source[i]));
    }
  }
  std::size_t size() const { return m_a.size(); }

  /** Pairs within the threshold under T (indices into `out` when given),
   *  and the sum of their squared residuals into `sumSq` when given. */
  std::size_t countInliers(
      const geometry::TRigid& T, std::vector<std::size_t>* out, double* sumSq) const
  {
    std::size_t c = 0;
    double s = 0;
    for (std::size_t i = 0; i < m_a.size(); ++i)
    {
      const double d2 = (T.R * m_b[i] + T.t - m_a[i]).squaredNorm();
      if (d2 < m_thr2)
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
  }

  /** The motion of a minimal sample, or nullopt when it cannot be rigid
   *  (a rigid motion preserves pairwise distances: the cheap rejection), its
   *  source points are closer than `minSpread` or collinear. */
  std::optional<geometry::TRigid> hypothesis(const std::size_t s[3], double minSpread) const
  {
    for (int p = 0; p < 3; ++p)
    {
      const int q = (p + 1) % 3;
      const double da = (m_a[s[p]] - m_a[s[q]]).norm(), db = (m_b[s[p]] - m_b[s[q]]).norm();
      if (std::abs(da - db) > 2 * m_thr || db < minSpread)
        return std::nullopt;
    }
    Eigen::Matrix3d A, B;
    for (int k = 0; k < 3; ++k)
    {
      A.col(k) = m_a[s[k]];
      B.col(k) = m_b[s[k]];
    }
    if (geometry::collinear(B))
      return std::nullopt;
    return geometry::alignRigid(A, B);
  }

  /** Least-squares refit on the inliers of T, repeated while the inlier set
   *  grows (at most 3 rounds); T and its inliers are updated. */
  void refine(geometry::TRigid& T, std::vector<std::size_t>& inl) const
  {
    inl.clear();
    countInliers(T, &inl, nullptr);
    for (int round = 0; round < 3; ++round)
    {
      const auto next = refit(m_a, m_b, inl);
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
  }

  /** Root mean square residual over `inl` under T. */
  double rmse(const geometry::TRigid& T, const std::vector<std::size_t>& inl) const
  {
    double sumSq = 0;
    for (auto i : inl)
      sumSq += (T.R * m_b[i] + T.t - m_a[i]).squaredNorm();
    return std::sqrt(sumSq / static_cast<double>(inl.size()));
  }

 private:
  std::vector<Eigen::Vector3d> m_a, m_b;
  double m_thr, m_thr2;
};

/** The best hypothesis of the sampling loop. */
struct TBestHypothesis
{
  geometry::TRigid T;
  std::size_t inliers = 0;
  int iterations = 0;
};

/** Three distinct random indices below n. */
void drawSample(
    std::mt19937& rng, std::uniform_int_distribution<std::size_t>& pick, std::size_t s[3])
{
  s[0] = pick(rng);
  do
    s[1] = pick(rng);
  while (s[1] == s[0]);
  do
    s[2] = pick(rng);
  while (s[2] == s[0] || s[2] == s[1]);
}

/** The sampling loop: most inliers (then smallest residual), stopping once
 *  `confidence` of one all-inlier sample is reached. */
TBestHypothesis sampleBest(const CRansacPairs& pairs, const CRigidTransformRansac::TOptions& o)
{
  const std::size_t n = pairs.size();
  const double minSpread = o.min_sample_spread * o.threshold_m;
  std::mt19937 rng(o.seed);
  std::uniform_int_distribution<std::size_t> pick(0, n - 1);
  TBestHypothesis best;
  double bestSumSq = std::numeric_limits<double>::max();
  int needed = o.max_iterations;
  const double logFail = std::log(1.0 - o.confidence);
  int it = 0;
  for (; it < needed && it < o.max_iterations; ++it)
  {
    std::size_t s[3];
    drawSample(rng, pick, s);
    const auto T = pairs.hypothesis(s, minSpread);
    if (!T)
      continue;
    double sumSq = 0;
    const std::size_t c = pairs.countInliers(*T, nullptr, &sumSq);
    if (c > best.inliers || (c == best.inliers && sumSq < bestSumSq))
    {
      best.inliers = c;
      bestSumSq = sumSq;
      best.T = *T;
      // Adaptive stop: iterations for `confidence` of one all-inlier sample.
      const double w = static_cast<double>(c) / static_cast<double>(n);
      const double pGood = w * w * w;
      if (pGood >= 1.0)
        needed = it + 1;
      else if (pGood > 0)
        needed = static_cast<int>(
            std::min<double>(o.max_iterations, std::ceil(logFail / std::log(1.0 - pGood))));
    }
  }
  best.iterations = it;
  return best;
}
}  // namespace

std::optional<TRigidRansacResult> CRigidTransformRansac::estimate(
    const std::vector<mrpt::math::TPoint3D>& target,
    const std::vector<mrpt::math::TPoint3D>& source) const
{
  if (target.size() != source.size())
    throw std::invalid_argument("CRigidTransformRansac::estimate: target and source sizes differ");
  const std::size_t minInliers =
      std::max<std::size_t>(3, static_cast<std::size_t>(m_options.min_inliers));
  if (target.size() < minInliers)
    return std::nullopt;
  const CRansacPairs pairs(target, source, m_options.threshold_m);
  const TBestHypothesis best = sampleBest(pairs, m_options);
  if (best.inliers < minInliers)
    return std::nullopt;
  geometry::TRigid T = best.T;
  std::vector<std::size_t> inl;
  pairs.refine(T, inl);
  if (inl.size() < minInliers)
    return std::nullopt;
  TRigidRansacResult res;
  res.transform = T.toPose();
  res.rmse = pairs.rmse(T, inl);
  res.inliers = std::move(inl);
  res.iterations = best.iterations;
  return res;
}
}  // namespace roislam::matching
