/* PNG figure of a trajectory's errors over time, from an evaluation's
 * per-pose samples (TEvaluationResult): top, the ATE of every associated
 * pose after the alignment, with its RMSE as a dashed line; bottom, the RPE
 * of every pose pair (translation on the left axis, rotation on the right).
 * A user sees where a run went wrong, not only how much. Used by the SLAM
 * app (errors.png, next to CTrajectoryPlot's ate.png) and roi-eval
 * --plot-errors. Runs gnuplot as CTrajectoryPlot does.
 *
 * Options (code only): title, width / height (px), gnuplot (executable).
 */
#pragma once

#include <roislam/evaluation/TEvaluationResult.h>

#include <string>

namespace roislam::evaluation
{
class CErrorPlot
{
 public:
  struct TOptions
  {
    std::string title;                //!< figure title (e.g. the sequence name)
    int width = 1400;                 //!< pixels
    int height = 700;                 //!< pixels
    std::string gnuplot = "gnuplot";  //!< executable (looked up in PATH)
  };

  CErrorPlot();
  /** Throws std::invalid_argument on a non-positive size. */
  explicit CErrorPlot(const TOptions& options);

  /** Writes `pngFile` (through a temporary name). Throws std::runtime_error
   *  when the result has no samples, gnuplot is missing or fails, or the
   *  file cannot be written. */
  void plot(const std::string& pngFile, const TEvaluationResult& result) const;

  const TOptions& options() const { return m_options; }

 private:
  TOptions m_options;
};
}  // namespace roislam::evaluation
