/* The roi-eval application as a library class (apps stay thin): loads a
 * ground-truth and an estimated TUM trajectory, evaluates them with
 * CTrajectoryEvaluator, prints a table or JSON, and optionally writes the
 * aligned estimate (TUM format), a PNG plot of the trajectories
 * (CTrajectoryPlot) and one of the errors over time (CErrorPlot). Given a
 * run's graph.graph and frames.csv it also checks the graph's edges against
 * the ground truth (edgeChi2, as summary.json's edge_chi2).
 */
#pragma once

#include <roislam/evaluation/CTrajectoryEvaluator.h>
#include <roislam/evaluation/EdgeChi2.h>
#include <roislam/evaluation/TEvaluationResult.h>

#include <optional>
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
    /** A run's graph.graph (io::loadGraphText) and its frames.csv (the
     *  keyframes' times, readFrameTimes): both or neither. */
    std::string graphFile, framesFile;
  };

  explicit CEvalApp(const TParams& params);

  /** Evaluates and writes the report to `out`. Throws std::runtime_error with a
   *  one-line message naming the file (and line) on bad input or output. */
  TEvaluationResult run(std::ostream& out);
  /** The graph's edge statistics of the last run() (with graphFile), else
   *  nullopt (also when no edge could be checked). */
  const std::optional<TEdgeChi2>& edgeChi2() const { return m_edgeChi2; }

 private:
  /** The graph's edges against `gt` (sorted): graphFile through
   *  io::loadGraphText, its nodes' times from framesFile. Throws naming the
   *  files when no edge can be checked. */
  TEdgeChi2 checkGraph(const io::TTrajectory& gt) const;

  TParams m_params;
  std::optional<TEdgeChi2> m_edgeChi2;
};
}  // namespace roislam::evaluation
