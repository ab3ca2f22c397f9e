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
 *
 * How much of a high chi² is the ground truth's own noise: the per-sample
 * noise of the ground truth, measured from its second differences
 * (groundTruthNoise), is added to each edge's covariance for a second set of
 * statistics (TEdgeChi2::withGroundTruthNoise). Only its white part shows
 * there; a time offset between the streams or a calibration error does not.
 * The frames' stamps carry their own jitter too (a driver's arrival time, not
 * the exposure's), and the ground truth is read at those stamps: a stamp dt
 * off reads the camera where it was dt away, its velocity times dt. That
 * jitter is measured from the frames' stamps the same way (stampJitter) and
 * added with each end's velocity from the ground truth. A steady offset
 * between the clocks does not show there either.
 */
#pragma once

#include <mrpt/graphs/CNetworkOfPoses.h>
#include <roislam/io/TumTrajectory.h>

#include <Eigen/Core>
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
  /** Mean Gaussian negative log-likelihood per edge, nats (metres and
   *  radians): 0.5 (chi² + log det Σ) + 3 log 2π. Unlike the chi² it also
   *  charges a covariance for being too wide, so of two noise models for
   *  the same edges the lower one fits them better. NaN when an edge's
   *  information is singular. */
  double nll = 0;
};

/** A ground truth's white noise per sample, isotropic in translation and
 *  in rotation (measured by groundTruthNoise). */
struct TGroundTruthNoise
{
  double sigmaM = 0;         //!< per axis, metres
  double sigmaRad = 0;       //!< per axis, radians
  std::size_t triplets = 0;  //!< evenly spaced sample triplets measured
  /** The frames' stamp jitter (stampJitter), s; 0: not measured. */
  double stampJitterS = 0;
  std::size_t stampTriplets = 0;
};

/** A series of stamps' white jitter about a steady clock. */
struct TStampJitter
{
  double sigmaS = 0;
  std::size_t triplets = 0;
};

struct TEdgeChi2 : TEdgeChi2Stats
{
  std::size_t skipped = 0;  //!< edges without (a node's stamp has no ground truth)
  double expected = 6;      //!< E[chi²(6)]
  /** Per evaluated edge, in the graph's edge order. */
  std::vector<double> chi2;
  /** The same statistics per edge kind (when the caller labels edges). */
  std::map<std::string, TEdgeChi2Stats> byKind;
  /** The ground truth's measured noise, and the statistics with it added to
   *  each edge's covariance (nullopt: too few evenly spaced samples). */
  std::optional<TGroundTruthNoise> groundTruthNoise;
  std::optional<TEdgeChi2Stats> withGroundTruthNoise;
  /** withGroundTruthNoise per edge kind (empty without the noise). */
  std::map<std::string, TEdgeChi2Stats> byKindWithGroundTruthNoise;
};

/** One edge's error against the truth. */
struct TEdgeError
{
  double chi2 = 0;
  std::array<double, 6> direction{};  //!< e_i² / Σ_ii
  /** log det Σ (NaN: singular information). */
  double logDetCovariance = 0;
};

/** The white noise of a ground truth (sorted by stamp), from its second
 *  differences over evenly spaced sample triplets (gaps within 20 % of each
 *  other): x[i+1] - 2 x[i] + x[i-1] has variance 6 sigma² for white noise,
 *  and the motion's own second difference is negligible at mocap rates
 *  (1 m/s² at 100 Hz: 0.1 mm). Rotation likewise, from the difference of
 *  consecutive relative rotations' logs. Root mean square, so glitches count
 *  as they count in an edge's error. nullopt below 10 triplets. */
std::optional<TGroundTruthNoise> groundTruthNoise(const io::TTrajectory& sorted);

/** The white jitter of stamps (sorted) about a steady clock, from second
 *  differences over consecutive intervals each within 50 % of the median
 *  interval (a dropped frame breaks a triplet): t[i+1] - 2 t[i] + t[i-1] has
 *  variance 6 sigma². Root mean square. nullopt below 10 triplets. */
std::optional<TStampJitter> stampJitter(const std::vector<double>& sorted);

/** A ground-truth pose's velocity at `stamp`: the body-frame twist
 *  [v; omega] (right perturbation per second) over +-h, nullopt where the
 *  ground truth has no pose within maxDifference of stamp +- h. */
std::optional<Eigen::Matrix<double, 6, 1>> groundTruthTwist(
    const io::TTrajectory& sorted, double stamp, double h = 0.02, double maxDifference = 0.02);

/** The covariance the ground truth's noise adds to a relative pose `truth`
 *  (both ends' noise, with the rotation noise of the first end moving the
 *  second's position by the lever arm), in the [x y z rx ry rz] of the
 *  edge's error. */
Eigen::Matrix<double, 6, 6> groundTruthCovariance(
    const mrpt::poses::CPose3D& truth, const TGroundTruthNoise& noise);

/** The same plus the frames' stamp jitter (noise.stampJitterS): each end read
 *  at a stamp off by the jitter, moved by its twist (groundTruthTwist) times
 *  it, the first end's motion entering as its noise does. */
Eigen::Matrix<double, 6, 6> groundTruthCovariance(
    const mrpt::poses::CPose3D& truth, const TGroundTruthNoise& noise,
    const Eigen::Matrix<double, 6, 1>& twistFrom, const Eigen::Matrix<double, 6, 1>& twistTo);

/** Chi² of every edge of `graph` against `groundTruth` (sorted; a node's pose
 *  at stamp(node), interpolated, |dt| <= maxDifference). `kind` (may be
 *  empty) labels each edge for TEdgeChi2::byKind. `frameStamps` (sorted, may
 *  be empty): every frame's stamp, whose jitter joins the ground truth's
 *  noise. nullopt when no edge could be evaluated. */
std::optional<TEdgeChi2> edgeChi2(
    const mrpt::graphs::CNetworkOfPoses3DInf& graph,
    const std::function<double(mrpt::graphs::TNodeID)>& stamp, const io::TTrajectory& groundTruth,
    double maxDifference = 0.02,
    const std::function<std::string(mrpt::graphs::TNodeID, mrpt::graphs::TNodeID)>& kind = {},
    const std::vector<double>& frameStamps = {});

/** The SE(3) pseudo-log error of one edge (mean, information) against the
 *  true relative pose. */
TEdgeError edgeError(
    const mrpt::poses::CPose3D& edge, const mrpt::math::CMatrixDouble66& information,
    const mrpt::poses::CPose3D& truth);

/** The same error under the edge's covariance plus `extraCovariance` (the
 *  ground truth's): information I (Id + C I)^-1, which is (Σ + C)^-1 and
 *  stays right where I is singular. */
TEdgeError edgeError(
    const mrpt::poses::CPose3D& edge, const mrpt::math::CMatrixDouble66& information,
    const mrpt::poses::CPose3D& truth, const Eigen::Matrix<double, 6, 6>& extraCovariance);

/** edgeError(...).chi2. */
double edgeChi2(
    const mrpt::poses::CPose3D& edge, const mrpt::math::CMatrixDouble66& information,
    const mrpt::poses::CPose3D& truth);

/** {"edges", "skipped", "median", "mean", "nll", "expected", "direction" [6],
 *  "by_kind": {kind: {"edges", "median", "mean", "nll", "direction",
 *  "with_ground_truth_noise": {the same} or null}},
 *  "ground_truth_noise": {"sigma_m", "sigma_deg", "triplets",
 *  "stamp_jitter_ms", "stamp_triplets"} or null,
 *  "with_ground_truth_noise": {"edges", "median", "mean", "nll",
 *  "direction"} or null}. */
nlohmann::json toJson(const TEdgeChi2& s);
}  // namespace roislam::evaluation
