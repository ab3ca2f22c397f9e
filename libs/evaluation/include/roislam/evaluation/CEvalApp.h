/* The roi-eval application as a library class (apps stay thin): loads a
 * ground-truth and an estimated TUM trajectory, evaluates them with
 * CTrajectoryEvaluator, prints a table or JSON, and optionally writes the
 * aligned estimate (TUM format), a PNG plot of the trajectories
 * (CTrajectoryPlot) and one of the errors over time (CErrorPlot).
 */
#pragma once

#include <roislam/evaluation/CTrajectoryEvaluator.h>
#include <roislam/evaluation/TEvaluationResult.h>

#include <ostream>
#include <string>

namespace roislam::evaluation
{
class CEvalApp
{
 public:
  struct TParams
  {
    std::string groundTruthFile;
    std::string estimateFile;
    CTrajectoryEvaluator::TOptions evaluation;
    bool json = false;          //!< one JSON object (toJson()) instead of a table
    std::string plotFile;       //!< PNG to write, or empty
    std::string errorPlotFile;  //!< PNG of the errors over time, or empty
    std::string alignedFile;    //!< aligned estimate (TUM) to write, or empty
    /** Skip lines with a NaN or a zero quaternion (the benchmark scripts'
     *  behaviour) instead of rejecting the file. */
    bool skipInvalid = false;
  };

  explicit CEvalApp(const TParams& params);

  /** Evaluates and writes the report to `out`. Throws std::runtime_error with a
   *  one-line message naming the file (and line) on bad input or output. */
  TEvaluationResult run(std::ostream& out) const;

 private:
  TParams m_params;
};
}  // namespace roislam::evaluation
