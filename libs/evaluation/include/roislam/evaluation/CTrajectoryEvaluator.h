/* Trajectory evaluation against ground truth with the exact semantics of the
 * TUM RGB-D benchmark's scripts (associate.py, evaluate_ate.py,
 * evaluate_rpe.py --fixed_delta). Used by roi-eval, the SLAM app (when the
 * ground truth is known) and the bench.
 *
 * Where we deliberately follow the scripts:
 *  - Input: both trajectories behave like the scripts' dicts keyed by stamp:
 *    sorted by stamp, a repeated stamp keeps its last pose.
 *  - ATE association (associate.py): every (gt, est) pair with
 *    |t_gt - (t_est + offset)| < max_difference is a candidate; candidates are
 *    taken greedily by smallest difference (ties by gt stamp, then est stamp),
 *    each stamp at most once (io::associateStamps(), called with a slightly
 *    wider window and filtered with the script's exact test, so that pairs
 *    whose double difference is just below max_difference are kept as the
 *    script keeps them).
 *  - ATE alignment (evaluate_ate.py align()): closed-form least-squares
 *    rotation + translation, no scale, of the associated estimated positions
 *    onto the ground-truth positions (Horn's problem, solved as the script does
 *    by SVD of the 3x3 correlation of the centred point sets, with the
 *    reflection fix S = diag(1,1,-1) when det(U) det(V) < 0). Only positions
 *    enter; the error per pair is |R p_est + t - p_gt|. rmse = sqrt(sum e^2/n),
 *    std = population std (numpy.std), median = numpy.median.
 *  - RPE (evaluate_rpe.py --fixed_delta, --max_pairs 0): with sorted stamps,
 *    for each estimate index i, j = find_closest_index(index, index[i] + delta)
 *    where index is the estimate stamps (delta_unit s) or 0..n-1 (f); the
 *    script's binary search is reproduced, including which of two equidistant
 *    neighbours it returns. The pair is dropped when j is the last index. Each
 *    estimate stamp maps to the ground-truth stamp closest to (stamp + offset)
 *    (same search); the pair is dropped when either distance exceeds
 *    2 x the median ground-truth stamp interval. Error =
 *    (E_i^-1 E_j)(G_i^-1 G_j)^-1; translational error = its translation norm;
 *    rotational error = acos(min(1, max(-1, (trace(R) - 1)/2))). The estimate
 *    is not aligned for RPE. The script's "too few overlapping stamps" check
 *    (fewer than 2 distinct round-trip matches) is reproduced.
 *  - Quaternions are normalised as evaluate_rpe.py does (io::loadTumTrajectory).
 * Where we deviate:
 *  - ATE needs at least 3 associated pairs (the script accepts 2, for which
 *    the rotation is not determined); RPE needs 2 pairs, as the script.
 *  - No random subsampling of RPE pairs (the script samples 10000 when there
 *    are more; our sequences have fewer).
 *  - Files (io::loadTumTrajectory): lines with NaN or an all-zero quaternion
 *    are skipped for ATE too (the ATE script keeps them, and a NaN makes its
 *    SVD fail); a line must have exactly 8 numbers, and an infinite value is
 *    an error (the scripts ignore extra columns and pass infinities on).
 *  - Rotational figures near zero carry the acos() rounding noise of the
 *    trace formula (about 1e-6 deg), as in the script, so two
 *    implementations agree there only to that level.
 *
 * ini section [TrajectoryEvaluation] (TOptions):
 *   max_difference  double > 0   0.02  s   ATE association window
 *   offset          double       0     s   added to estimate stamps (t_est + offset)
 *   delta           double > 0   1         RPE pair distance, in delta_unit
 *   delta_unit      s|f          s         seconds or frames (estimate indices)
 * A bad value throws std::invalid_argument naming the section and key.
 */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <roislam/evaluation/TEvaluationResult.h>
#include <roislam/io/TumTrajectory.h>

#include <string>

namespace roislam::evaluation
{
class CTrajectoryEvaluator
{
 public:
  enum class TDeltaUnit
  {
    Seconds,
    Frames
  };

  struct TOptions : public mrpt::config::CLoadableOptions
  {
    double max_difference = 0.02;  //!< s
    double offset = 0;             //!< s, added to estimate stamps
    double delta = 1;              //!< in delta_unit
    TDeltaUnit delta_unit = TDeltaUnit::Seconds;

    /** Throws std::invalid_argument "[<section>] <key>: ..." on a bad value;
     *  `section` is used only in messages. */
    void validate(const std::string& section = "TrajectoryEvaluation") const;
    void loadFromConfigFile(
        const mrpt::config::CConfigFileBase& cfg, const std::string& section) override;
    void saveToConfigFile(
        mrpt::config::CConfigFileBase& cfg, const std::string& section) const override;
  };

  // Two constructors: GCC rejects TOptions() as a default argument here.
  CTrajectoryEvaluator();
  /** Throws std::invalid_argument on invalid options. */
  explicit CTrajectoryEvaluator(const TOptions& options);

  /** ATE and RPE of `est` against `gt` (inputs need not be sorted). Throws
   *  std::runtime_error with a one-line reason when a trajectory is empty,
   *  fewer than 3 stamps associate, or fewer than 2 RPE pairs remain. */
  TEvaluationResult evaluate(const io::TTrajectory& gt, const io::TTrajectory& est) const;

  const TOptions& options() const { return m_options; }

 private:
  TOptions m_options;
};

/** "s" or "f". */
std::string toString(CTrajectoryEvaluator::TDeltaUnit unit);
/** Parses "s" / "f"; throws std::invalid_argument otherwise. */
CTrajectoryEvaluator::TDeltaUnit deltaUnitFromString(const std::string& text);
}  // namespace roislam::evaluation
