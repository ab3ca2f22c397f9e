#include "roislam/evaluation/EdgeChi2.h"

#include <mrpt/math/geometry.h>
#include <roislam/common/Median.h>
#include <roislam/geometry/Rotation.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>

namespace roislam::evaluation
{
namespace
{
TEdgeChi2Stats statsOf(const std::vector<TEdgeError>& errors)
{
  TEdgeChi2Stats s;
  s.edges = errors.size();
  if (errors.empty())
    return s;
  std::vector<double> sorted;
  for (const auto& e : errors)
  {
    sorted.push_back(e.chi2);
    s.nll += (0.5 * (e.chi2 + e.logDetCovariance) + 3.0 * std::log(2.0 * M_PI)) /
             static_cast<double>(errors.size());
    for (int k = 0; k < 6; ++k)
      s.direction[k] += e.direction[k] / static_cast<double>(errors.size());
  }
  std::sort(sorted.begin(), sorted.end());
  const std::size_t n = sorted.size();
  s.median = n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
  s.mean = std::accumulate(sorted.begin(), sorted.end(), 0.0) / static_cast<double>(n);
  return s;
}

nlohmann::json statsJson(const TEdgeChi2Stats& s)
{
  return {
      {"edges", s.edges},
      {"median", s.median},
      {"mean", s.mean},
      {"nll", std::isfinite(s.nll) ? nlohmann::json(s.nll) : nlohmann::json(nullptr)},
      {"direction", std::vector<double>(s.direction.begin(), s.direction.end())}};
}

/** The residual SPA minimises: pseudo-log of inv(D) (+) (P2 (-) P1), i.e.
 *  [translation, rotation vector] (MRPT's SO<3>::log gives NaN when rounding
 *  puts the trace a hair above 3, as it does for exact edges). */
Eigen::Matrix<double, 6, 1> residual(
    const mrpt::poses::CPose3D& edge, const mrpt::poses::CPose3D& truth)
{
  const mrpt::poses::CPose3D E = truth - edge;
  Eigen::Matrix<double, 6, 1> e;
  e.head<3>() << E.x(), E.y(), E.z();
  e.tail<3>() = geometry::logSO3(E.getRotationMatrix().asEigen());
  return e;
}

TEdgeError errorUnder(const Eigen::Matrix<double, 6, 1>& e, const Eigen::Matrix<double, 6, 6>& I)
{
  TEdgeError out;
  out.chi2 = e.dot(I * e);
  // A singular information (a direction it claims nothing about) gives an
  // infinite marginal variance there: that direction reads 0.
  const Eigen::Matrix<double, 6, 6> S = I.completeOrthogonalDecomposition().pseudoInverse();
  for (int k = 0; k < 6; ++k)
    out.direction[k] = S(k, k) > 0 ? e[k] * e[k] / S(k, k) : 0.0;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eig(I);
  const auto& lambda = eig.eigenvalues();
  out.logDetCovariance = lambda.minCoeff() > 0 ? -lambda.array().log().sum()
                                               : std::numeric_limits<double>::quiet_NaN();
  return out;
}

/** How a right perturbation (p, phi) of the first end of the relative pose
 *  T = inv(A) B = (R, t) enters T's error: (-R^T p + [R^T t]x R^T phi,
 *  -R^T phi); its rotation swings B's position by the lever arm t. (B's own
 *  perturbation enters as it is.) */
Eigen::Matrix<double, 6, 6> firstEndJacobian(const mrpt::poses::CPose3D& truth)
{
  const Eigen::Matrix3d R = truth.getRotationMatrix().asEigen();
  const Eigen::Vector3d u = R.transpose() * Eigen::Vector3d(truth.x(), truth.y(), truth.z());
  Eigen::Matrix<double, 6, 6> J = Eigen::Matrix<double, 6, 6>::Zero();
  J.topLeftCorner<3, 3>() = -R.transpose();
  J.topRightCorner<3, 3>() = mrpt::math::skew_symmetric3(u).asEigen() * R.transpose();
  J.bottomRightCorner<3, 3>() = -R.transpose();
  return J;
}
}  // namespace

TEdgeError edgeError(
    const mrpt::poses::CPose3D& edge, const mrpt::math::CMatrixDouble66& information,
    const mrpt::poses::CPose3D& truth)
{
  return errorUnder(residual(edge, truth), information.asEigen());
}

TEdgeError edgeError(
    const mrpt::poses::CPose3D& edge, const mrpt::math::CMatrixDouble66& information,
    const mrpt::poses::CPose3D& truth, const Eigen::Matrix<double, 6, 6>& extraCovariance)
{
  const Eigen::Matrix<double, 6, 6>& I = information.asEigen();
  const Eigen::Matrix<double, 6, 6> A =
      Eigen::Matrix<double, 6, 6>::Identity() + extraCovariance * I;
  Eigen::Matrix<double, 6, 6> combined = I * A.inverse();
  combined = 0.5 * (combined + combined.transpose()).eval();
  return errorUnder(residual(edge, truth), combined);
}

std::optional<TGroundTruthNoise> groundTruthNoise(const io::TTrajectory& sorted)
{
  double sumT = 0, sumR = 0;
  std::size_t n = 0;
  for (std::size_t i = 1; i + 1 < sorted.size(); ++i)
  {
    const auto &a = sorted[i - 1], &b = sorted[i], &c = sorted[i + 1];
    const double dt1 = b.timestamp - a.timestamp, dt2 = c.timestamp - b.timestamp;
    if (!(dt1 > 0 && dt2 > 0) || std::abs(dt1 - dt2) > 0.2 * std::min(dt1, dt2))
      continue;
    const Eigen::Vector3d ta(a.pose.x(), a.pose.y(), a.pose.z()),
        tb(b.pose.x(), b.pose.y(), b.pose.z()), tc(c.pose.x(), c.pose.y(), c.pose.z());
    const Eigen::Matrix3d Ra = a.pose.getRotationMatrix().asEigen(),
                          Rb = b.pose.getRotationMatrix().asEigen(),
                          Rc = c.pose.getRotationMatrix().asEigen();
    const Eigen::Vector3d w1 = geometry::logSO3(Ra.transpose() * Rb),
                          w2 = geometry::logSO3(Rb.transpose() * Rc);
    sumT += (tc - 2 * tb + ta).squaredNorm();
    sumR += (w2 - w1).squaredNorm();
    ++n;
  }
  if (n < 10)
    return std::nullopt;
  // Per axis: a second difference of white noise has variance 6 sigma².
  TGroundTruthNoise g;
  g.sigmaM = std::sqrt(sumT / (3.0 * static_cast<double>(n)) / 6.0);
  g.sigmaRad = std::sqrt(sumR / (3.0 * static_cast<double>(n)) / 6.0);
  g.triplets = n;
  return g;
}

Eigen::Matrix<double, 6, 6> groundTruthCovariance(
    const mrpt::poses::CPose3D& truth, const TGroundTruthNoise& noise)
{
  const double vt = noise.sigmaM * noise.sigmaM, vr = noise.sigmaRad * noise.sigmaRad;
  Eigen::Matrix<double, 6, 1> v;
  v << vt, vt, vt, vr, vr, vr;
  const Eigen::Matrix<double, 6, 6> J = firstEndJacobian(truth);
  Eigen::Matrix<double, 6, 6> C = J * v.asDiagonal() * J.transpose();
  C.diagonal() += v;
  return C;
}

Eigen::Matrix<double, 6, 6> groundTruthCovariance(
    const mrpt::poses::CPose3D& truth, const TGroundTruthNoise& noise,
    const Eigen::Matrix<double, 6, 1>& twistFrom, const Eigen::Matrix<double, 6, 1>& twistTo)
{
  // A stamp off by dt perturbs its end on the right by twist * dt; the two
  // ends' stamps jitter independently.
  const double vs = noise.stampJitterS * noise.stampJitterS;
  const Eigen::Matrix<double, 6, 1> a = firstEndJacobian(truth) * twistFrom;
  return groundTruthCovariance(truth, noise) +
         vs * (a * a.transpose() + twistTo * twistTo.transpose());
}

std::optional<TStampJitter> stampJitter(const std::vector<double>& sorted)
{
  if (sorted.size() < 3)
    return std::nullopt;
  std::vector<double> intervals;
  for (std::size_t i = 1; i < sorted.size(); ++i)
    intervals.push_back(sorted[i] - sorted[i - 1]);
  const double period = common::upperMedian(std::move(intervals));
  if (!(period > 0))
    return std::nullopt;
  // A dropped frame doubles an interval; jitter moves it by a few percent.
  // The gate is wide so that it does not cut the jitter's own tails (a gate
  // at 20 % read 2 ms of jitter at 30 Hz as 1.3 ms).
  const auto regular = [period](double dt) { return std::abs(dt - period) < 0.5 * period; };
  double sum = 0;
  std::size_t n = 0;
  for (std::size_t i = 1; i + 1 < sorted.size(); ++i)
  {
    const double dt1 = sorted[i] - sorted[i - 1], dt2 = sorted[i + 1] - sorted[i];
    if (!regular(dt1) || !regular(dt2))
      continue;
    sum += (dt2 - dt1) * (dt2 - dt1);
    ++n;
  }
  if (n < 10)
    return std::nullopt;
  return TStampJitter{std::sqrt(sum / static_cast<double>(n) / 6.0), n};
}

std::optional<Eigen::Matrix<double, 6, 1>> groundTruthTwist(
    const io::TTrajectory& sorted, double stamp, double h, double maxDifference)
{
  const auto a = io::poseAt(sorted, stamp - h, maxDifference);
  const auto b = io::poseAt(sorted, stamp + h, maxDifference);
  if (!a || !b || !(h > 0))
    return std::nullopt;
  const mrpt::poses::CPose3D d = *b - *a;
  Eigen::Matrix<double, 6, 1> xi;
  xi.head<3>() << d.x(), d.y(), d.z();
  xi.tail<3>() = geometry::logSO3(d.getRotationMatrix().asEigen());
  return xi / (2 * h);
}

double edgeChi2(
    const mrpt::poses::CPose3D& edge, const mrpt::math::CMatrixDouble66& information,
    const mrpt::poses::CPose3D& truth)
{
  return edgeError(edge, information, truth).chi2;
}

std::optional<TEdgeChi2> edgeChi2(
    const mrpt::graphs::CNetworkOfPoses3DInf& graph,
    const std::function<double(mrpt::graphs::TNodeID)>& stamp, const io::TTrajectory& groundTruth,
    double maxDifference,
    const std::function<std::string(mrpt::graphs::TNodeID, mrpt::graphs::TNodeID)>& kind,
    const std::vector<double>& frameStamps)
{
  TEdgeChi2 s;
  s.groundTruthNoise = groundTruthNoise(groundTruth);
  const auto jitter = stampJitter(frameStamps);
  if (s.groundTruthNoise && jitter)
  {
    s.groundTruthNoise->stampJitterS = jitter->sigmaS;
    s.groundTruthNoise->stampTriplets = jitter->triplets;
  }
  std::vector<TEdgeError> all, withNoise;
  std::map<std::string, std::vector<TEdgeError>> kinds, kindsWithNoise;
  for (const auto& [ids, edge] : graph.edges)
  {
    const auto a = io::poseAt(groundTruth, stamp(ids.first), maxDifference);
    const auto b = io::poseAt(groundTruth, stamp(ids.second), maxDifference);
    if (!a || !b)
    {
      ++s.skipped;
      continue;
    }
    const mrpt::poses::CPose3D truth = *b - *a;
    all.push_back(edgeError(edge.mean, edge.cov_inv, truth));
    if (s.groundTruthNoise)
    {
      // Without a measured jitter, or a velocity at either end (the ground
      // truth's edge), the jitter's term is left out for this edge.
      std::optional<Eigen::Matrix<double, 6, 1>> va, vb;
      if (s.groundTruthNoise->stampJitterS > 0)
      {
        va = groundTruthTwist(groundTruth, stamp(ids.first));
        vb = groundTruthTwist(groundTruth, stamp(ids.second));
      }
      const Eigen::Matrix<double, 6, 6> C =
          va && vb ? groundTruthCovariance(truth, *s.groundTruthNoise, *va, *vb)
                   : groundTruthCovariance(truth, *s.groundTruthNoise);
      withNoise.push_back(edgeError(edge.mean, edge.cov_inv, truth, C));
    }
    s.chi2.push_back(all.back().chi2);
    if (kind)
    {
      const std::string k = kind(ids.first, ids.second);
      kinds[k].push_back(all.back());
      if (s.groundTruthNoise)
        kindsWithNoise[k].push_back(withNoise.back());
    }
  }
  if (all.empty())
    return std::nullopt;
  static_cast<TEdgeChi2Stats&>(s) = statsOf(all);
  for (const auto& [k, errors] : kinds)
    s.byKind[k] = statsOf(errors);
  if (s.groundTruthNoise)
    s.withGroundTruthNoise = statsOf(withNoise);
  for (const auto& [k, errors] : kindsWithNoise)
    s.byKindWithGroundTruthNoise[k] = statsOf(errors);
  return s;
}

nlohmann::json toJson(const TEdgeChi2& s)
{
  nlohmann::json j = statsJson(s);
  j["skipped"] = s.skipped;
  j["expected"] = s.expected;
  nlohmann::json kinds = nlohmann::json::object();
  for (const auto& [k, st] : s.byKind)
  {
    kinds[k] = statsJson(st);
    const auto it = s.byKindWithGroundTruthNoise.find(k);
    kinds[k]["with_ground_truth_noise"] =
        it == s.byKindWithGroundTruthNoise.end() ? nlohmann::json(nullptr) : statsJson(it->second);
  }
  j["by_kind"] = kinds;
  j["ground_truth_noise"] = nullptr;
  if (s.groundTruthNoise)
    j["ground_truth_noise"] = {
        {"sigma_m", s.groundTruthNoise->sigmaM},
        {"sigma_deg", s.groundTruthNoise->sigmaRad * 180.0 / M_PI},
        {"triplets", s.groundTruthNoise->triplets},
        {"stamp_jitter_ms", s.groundTruthNoise->stampJitterS * 1e3},
        {"stamp_triplets", s.groundTruthNoise->stampTriplets}};
  j["with_ground_truth_noise"] =
      s.withGroundTruthNoise ? statsJson(*s.withGroundTruthNoise) : nlohmann::json(nullptr);
  return j;
}
}  // namespace roislam::evaluation
