#include "roislam/evaluation/EdgeChi2.h"

#include <roislam/geometry/Rotation.h>

#include <Eigen/Dense>
#include <algorithm>
#include <numeric>

namespace roislam::evaluation
{
double edgeChi2(
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
  return e.dot(information.asEigen() * e);
}

std::optional<TEdgeChi2> edgeChi2(
    const mrpt::graphs::CNetworkOfPoses3DInf& graph,
    const std::function<double(mrpt::graphs::TNodeID)>& stamp, const io::TTrajectory& groundTruth,
    double maxDifference)
{
  TEdgeChi2 s;
  for (const auto& [ids, edge] : graph.edges)
  {
    const auto a = io::poseAt(groundTruth, stamp(ids.first), maxDifference);
    const auto b = io::poseAt(groundTruth, stamp(ids.second), maxDifference);
    if (!a || !b)
    {
      ++s.skipped;
      continue;
    }
    s.chi2.push_back(edgeChi2(edge.mean, edge.cov_inv, *b - *a));
  }
  s.edges = s.chi2.size();
  if (s.chi2.empty())
    return std::nullopt;
  std::vector<double> sorted = s.chi2;
  std::sort(sorted.begin(), sorted.end());
  const std::size_t n = sorted.size();
  s.median = n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
  s.mean = std::accumulate(sorted.begin(), sorted.end(), 0.0) / static_cast<double>(n);
  return s;
}

nlohmann::json toJson(const TEdgeChi2& s)
{
  return {
      {"edges", s.edges},
      {"skipped", s.skipped},
      {"median", s.median},
      {"mean", s.mean},
      {"expected", s.expected}};
}
}  // namespace roislam::evaluation
