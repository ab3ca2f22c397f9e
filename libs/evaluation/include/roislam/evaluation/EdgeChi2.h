/* How honest a pose graph's edge information is: each edge's chi² against the
 * ground truth's relative pose, in the parametrisation MRPT's SPA
 * (optimize_graph_spa_levmarq) weights, the SE(3) pseudo-logarithm
 * e = [x y z rx ry rz] of inv(edge) (+) inv(gt_from) (+) gt_to. An edge whose
 * information is its estimator's true inverse covariance has chi² ~ chi²(6):
 * mean 6, median 5.35. Ground truth's own noise (mocap, time association)
 * adds to it, so real data reads a little high. Read by roi-graphslam
 * (summary.json "edge_chi2") and its tests.
 */
#pragma once

#include <mrpt/graphs/CNetworkOfPoses.h>
#include <roislam/io/TumTrajectory.h>

#include <cstddef>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

namespace roislam::evaluation
{
struct TEdgeChi2
{
  std::size_t edges = 0;    //!< edges whose two nodes have a ground-truth pose
  std::size_t skipped = 0;  //!< edges without (a node's stamp has no ground truth)
  double median = 0, mean = 0;
  double expected = 6;  //!< E[chi²(6)]
  /** Per evaluated edge, in the graph's edge order. */
  std::vector<double> chi2;
};

/** Chi² of every edge of `graph` against `groundTruth` (sorted; a node's pose
 *  at stamp(node), interpolated, |dt| <= maxDifference). nullopt when no edge
 *  could be evaluated. */
std::optional<TEdgeChi2> edgeChi2(
    const mrpt::graphs::CNetworkOfPoses3DInf& graph,
    const std::function<double(mrpt::graphs::TNodeID)>& stamp, const io::TTrajectory& groundTruth,
    double maxDifference = 0.02);

/** The SE(3) pseudo-log chi² of one edge (mean, information) against the
 *  true relative pose. */
double edgeChi2(
    const mrpt::poses::CPose3D& edge, const mrpt::math::CMatrixDouble66& information,
    const mrpt::poses::CPose3D& truth);

/** {"edges", "skipped", "median", "mean", "expected"}. */
nlohmann::json toJson(const TEdgeChi2& s);
}  // namespace roislam::evaluation
