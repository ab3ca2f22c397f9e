#include "roislam/evaluation/EdgeChi2.h"

#include <roislam/geometry/Rotation.h>

#include <Eigen/Dense>
#include <algorithm>
#include <numeric>

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
      {"direction", std::vector<double>(s.direction.begin(), s.direction.end())}};
}
}  // namespace

TEdgeError edgeError(
    const mrpt::poses::CPose3D& edge, const mrpt::math::CMatrixDouble66& information,
    const mrpt::poses::CPose3D& truth)
{
  // The residual SPA minimises: pseudo-log of inv(D) (+) (P2 (-) P1), i.e.
  // [translation, rotation vector] (MRPT's SO<3>::log gives NaN when rounding
  // puts the trace a hair above 3, as it does for exact edges).
  const mrpt::poses::CPose3D E = truth - edge;
  Eigen::Matrix<double, 6, 1> e;
  e.head<3>() << E.x(), E.y(), E.z();
  e.tail<3>() = geometry::logSO3(E.getRotationMatrix().asEigen());
  const Eigen::Matrix<double, 6, 6>& I = information.asEigen();
  TEdgeError out;
  out.chi2 = e.dot(I * e);
  // A singular information (a direction it claims nothing about) gives an
  // infinite marginal variance there: that direction reads 0.
  const Eigen::Matrix<double, 6, 6> S = I.completeOrthogonalDecomposition().pseudoInverse();
  for (int k = 0; k < 6; ++k)
    out.direction[k] = S(k, k) > 0 ? e[k] * e[k] / S(k, k) : 0.0;
  return out;
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
    const std::function<std::string(mrpt::graphs::TNodeID, mrpt::graphs::TNodeID)>& kind)
{
  TEdgeChi2 s;
  std::vector<TEdgeError> all;
  std::map<std::string, std::vector<TEdgeError>> kinds;
  for (const auto& [ids, edge] : graph.edges)
  {
    const auto a = io::poseAt(groundTruth, stamp(ids.first), maxDifference);
    const auto b = io::poseAt(groundTruth, stamp(ids.second), maxDifference);
    if (!a || !b)
    {
      ++s.skipped;
      continue;
    }
    all.push_back(edgeError(edge.mean, edge.cov_inv, *b - *a));
    s.chi2.push_back(all.back().chi2);
    if (kind)
      kinds[kind(ids.first, ids.second)].push_back(all.back());
  }
  if (all.empty())
    return std::nullopt;
  static_cast<TEdgeChi2Stats&>(s) = statsOf(all);
  for (const auto& [k, errors] : kinds)
    s.byKind[k] = statsOf(errors);
  return s;
}

nlohmann::json toJson(const TEdgeChi2& s)
{
  nlohmann::json j = statsJson(s);
  j["skipped"] = s.skipped;
  j["expected"] = s.expected;
  nlohmann::json kinds = nlohmann::json::object();
  for (const auto& [k, st] : s.byKind)
    kinds[k] = statsJson(st);
  j["by_kind"] = kinds;
  return j;
}
}  // namespace roislam::evaluation
