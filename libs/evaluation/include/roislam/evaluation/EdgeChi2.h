/* How honest a pose graph's edge information is: each edge's chi² against the
 * ground truth's relative pose, in the parametrisation MRPT's SPA
 * (optimize_graph_spa_levmarq) weights, the SE(3) pseudo-logarithm
 * e = [x y z rx ry rz] of inv(edge) (+) inv(gt_from) (+) gt_to. An edge whose
 * information is its estimator's true inverse covariance has chi² ~ chi²(6):
 * mean 6, median 5.35. Ground truth's own noise (mocap, time association)
 * adds to it, so real data reads a little high. Per direction, e_i² / Σ_ii
 * (Σ = the information's inverse) has mean 1: it tells which directions an
 * information is overconfident in; per edge kind (the caller's labels, e.g.
 * odometry / keyframe / loop) which edges. Read by CSlamRunner
 * (summary.json "edge_chi2") and its tests.
 */
#pragma once

#include <mrpt/graphs/CNetworkOfPoses.h>
#include <roislam/io/TumTrajectory.h>

#include <array>
#include <cstddef>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace roislam::evaluation
{
/** The statistics of a set of edges. */
struct TEdgeChi2Stats
{
  std::size_t edges = 0;
  double median = 0, mean = 0;
  /** Mean of e_i² / Σ_ii per direction [x y z rx ry rz] (expected 1). */
  std::array<double, 6> direction{};
};

struct TEdgeChi2 : TEdgeChi2Stats
{
  std::size_t skipped = 0;  //!< edges without (a node's stamp has no ground truth)
  double expected = 6;      //!< E[chi²(6)]
  /** Per evaluated edge, in the graph's edge order. */
  std::vector<double> chi2;
  /** The same statistics per edge kind (when the caller labels edges). */
  std::map<std::string, TEdgeChi2Stats> byKind;
};

/** One edge's error against the truth. */
struct TEdgeError
{
  double chi2 = 0;
  std::array<double, 6> direction{};  //!< e_i² / Σ_ii
};

/** Chi² of every edge of `graph` against `groundTruth` (sorted; a node's pose
 *  at stamp(node), interpolated, |dt| <= maxDifference). `kind` (may be
 *  empty) labels each edge for TEdgeChi2::byKind. nullopt when no edge could
 *  be evaluated. */
std::optional<TEdgeChi2> edgeChi2(
    const mrpt::graphs::CNetworkOfPoses3DInf& graph,
    const std::function<double(mrpt::graphs::TNodeID)>& stamp, const io::TTrajectory& groundTruth,
    double maxDifference = 0.02,
    const std::function<std::string(mrpt::graphs::TNodeID, mrpt::graphs::TNodeID)>& kind = {});

/** The SE(3) pseudo-log error of one edge (mean, information) against the
 *  true relative pose. */
TEdgeError edgeError(
    const mrpt::poses::CPose3D& edge, const mrpt::math::CMatrixDouble66& information,
    const mrpt::poses::CPose3D& truth);

/** edgeError(...).chi2. */
double edgeChi2(
    const mrpt::poses::CPose3D& edge, const mrpt::math::CMatrixDouble66& information,
    const mrpt::poses::CPose3D& truth);

/** {"edges", "skipped", "median", "mean", "expected", "direction" [6],
 *  "by_kind": {kind: {"edges", "median", "mean", "direction"}}}. */
nlohmann::json toJson(const TEdgeChi2& s);
}  // namespace roislam::evaluation
