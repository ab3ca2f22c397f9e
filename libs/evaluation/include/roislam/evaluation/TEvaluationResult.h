/* Results of CTrajectoryEvaluator::evaluate(): absolute trajectory error (ATE)
 * and relative pose error (RPE) as the TUM RGB-D benchmark's evaluate_ate.py
 * and evaluate_rpe.py --fixed_delta report them, plus the aligned estimate.
 * Read by roi-eval, the SLAM app and the bench; toJson() gives the layout that
 * `roi-eval --json` prints.
 */
#pragma once

#include <mrpt/poses/CPose3D.h>
#include <roislam/io/TumTrajectory.h>

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace roislam::evaluation
{
/** Translational error of each associated pose after alignment, in metres.
 *  std is the population standard deviation (numpy.std); median averages the
 *  two middle values of an even count (numpy.median). */
struct TAteResult
{
  /** One associated pose: the estimate's stamp and its error after alignment (m). */
  struct TSample
  {
    double timestamp = 0, error = 0;
  };

  double rmse = 0, mean = 0, median = 0, std = 0, min = 0, max = 0;
  std::size_t pairs = 0;  //!< associated (ground truth, estimate) pairs
  /** The rigid transform applied to the estimate: aligned = alignment (+) estimate. */
  mrpt::poses::CPose3D alignment;
  /** Every associated pose's error, sorted by stamp (the error-over-time plot). */
  std::vector<TSample> samples;
  /** Not a benchmark figure: the RMSE after the best alignment that may also
   *  mirror the estimate (a reflection, then a rigid motion). Far below rmse
   *  when the estimate and the ground truth use opposite axis conventions,
   *  e.g. ICL-NUIM's y-up ground truth with a camera given fy > 0
   *  (mirrorWarning()). */
  double mirrored_rmse = 0;
};

/** A one-line warning when the estimate fits the ground truth far better
 *  mirrored (mirrored_rmse below half of rmse), else empty. */
std::string mirrorWarning(const TAteResult& ate);

/** Relative pose errors over pose pairs `delta` apart. Translation in metres,
 *  rotation in degrees (the script's rotational median is printed in radians
 *  by mistake; here every rotational figure is in degrees). */
struct TRpeResult
{
  /** One compared pose pair, at the stamp of its first estimated pose. */
  struct TSample
  {
    double timestamp = 0, trans = 0, rot_deg = 0;  //!< m, deg
  };

  double trans_rmse = 0, trans_mean = 0, trans_median = 0, trans_std = 0, trans_min = 0,
         trans_max = 0;
  double rot_rmse_deg = 0, rot_mean_deg = 0, rot_median_deg = 0, rot_std_deg = 0, rot_min_deg = 0,
         rot_max_deg = 0;
  std::size_t pairs = 0;  //!< compared pose pairs
  /** Every compared pair's error, sorted by stamp (the RPE-over-time plot). */
  std::vector<TSample> samples;
};

struct TEvaluationResult
{
  TAteResult ate;
  TRpeResult rpe;
  /** Every estimated pose (sorted by stamp, repeated stamps removed) moved by
   *  ate.alignment into the ground-truth frame. */
  io::TTrajectory aligned;
};

/** {"ate":{"rmse","mean","median","std","min","max","pairs","mirrored_rmse"},
 *   "rpe":{"trans_rmse","trans_mean","trans_median","trans_std","trans_min","trans_max",
 *          "rot_rmse_deg","rot_mean_deg","rot_median_deg","rot_std_deg","rot_min_deg",
 *          "rot_max_deg","pairs"}}  (metres, degrees). */
nlohmann::json toJson(const TEvaluationResult& result);
}  // namespace roislam::evaluation
