#include "roislam/evaluation/CEvalApp.h"

#include <roislam/evaluation/CErrorPlot.h>
#include <roislam/evaluation/CTrajectoryPlot.h>
#include <roislam/evaluation/FramesCsv.h>
#include <roislam/io/GraphText.h>

#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace roislam::evaluation
{
namespace
{
std::string fixed(double v, int decimals)
{
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.*f", decimals, v);
  return buf;
}

/** The table's block for a checked graph (CEvalApp::checkGraph). */
void printEdges(std::ostream& out, const TEdgeChi2& c)
{
  out << "EDGES " << c.edges << " checked, " << c.skipped
      << " skipped (chi-square of each edge against the ground truth; chi2(6): median 5.35, "
         "mean 6)\n"
      << "     chi2 median " << fixed(c.median, 3) << "  mean " << fixed(c.mean, 3) << "\n";
  if (c.withGroundTruthNoise)
    out << "     with the ground truth's noise: median " << fixed(c.withGroundTruthNoise->median, 3)
        << "  mean " << fixed(c.withGroundTruthNoise->mean, 3) << "\n";
}
}  // namespace

CEvalApp::CEvalApp(const TParams& params) : m_params(params)
{
  m_params.evaluation.validate("command line");
  if (m_params.graphFile.empty() != m_params.framesFile.empty())
    throw std::invalid_argument(
        "--graph and --frames go together: the run's graph.graph and its frames.csv (which "
        "frame each graph node is)");
}

TEdgeChi2 CEvalApp::checkGraph(const io::TTrajectory& gt) const
{
  const auto graph = io::loadGraphText(m_params.graphFile);
  const TFrameTimes times = readFrameTimes(m_params.framesFile);
  // As the run does (CSlamRunner::edgeChi2), without the edge kinds, which
  // the file does not keep.
  auto chi2 = evaluation::edgeChi2(
      graph,
      [&times](mrpt::graphs::TNodeID id)
      {
        const auto it = times.keyframes.find(id);
        return it == times.keyframes.end() ? -1.0 : it->second;
      },
      gt, 0.02, {}, times.frames);
  if (!chi2)
    throw std::runtime_error(
        m_params.graphFile + ": no edge could be checked (none has both nodes in " +
        m_params.framesFile + " with ground truth in " + m_params.groundTruthFile + ")");
  return *chi2;
}

TEvaluationResult CEvalApp::run(std::ostream& out)
{
  const auto invalid = m_params.skipInvalid ? io::EInvalidPose::Skip : io::EInvalidPose::Reject;
  const io::TTrajectory gt = io::loadTumTrajectory(m_params.groundTruthFile, invalid);
  const io::TTrajectory est = io::loadTumTrajectory(m_params.estimateFile, invalid);
  if (gt.empty())
    throw std::runtime_error(m_params.groundTruthFile + ": no valid poses");
  if (est.empty())
    throw std::runtime_error(m_params.estimateFile + ": no valid poses");

  TEvaluationResult r;
  try
  {
    r = CTrajectoryEvaluator(m_params.evaluation).evaluate(gt, est);
  }
  catch (const std::runtime_error& e)
  {
    throw std::runtime_error(
        m_params.estimateFile + " vs " + m_params.groundTruthFile + ": " + e.what());
  }

  m_edgeChi2.reset();
  if (!m_params.graphFile.empty())
    m_edgeChi2 = checkGraph(gt);

  if (!m_params.alignedFile.empty())
    io::saveTumTrajectory(
        m_params.alignedFile, r.aligned,
        "estimate " + m_params.estimateFile + " aligned onto " + m_params.groundTruthFile +
            " (ATE rigid alignment, roi-eval)");
  if (!m_params.plotFile.empty())
  {
    CTrajectoryPlot::TOptions po;
    po.title = std::filesystem::path(m_params.estimateFile).filename().string() + "  (ATE rmse " +
               fixed(r.ate.rmse, 4) + " m)";
    CTrajectoryPlot(po).plot(m_params.plotFile, gt, {{"estimate (aligned)", r.aligned}});
  }
  if (!m_params.errorPlotFile.empty())
  {
    CErrorPlot::TOptions eo;
    eo.title = std::filesystem::path(m_params.estimateFile).filename().string();
    CErrorPlot(eo).plot(m_params.errorPlotFile, r);
  }

  if (m_params.json)
  {
    auto j = toJson(r);
    if (m_edgeChi2)
      j["edge_chi2"] = toJson(*m_edgeChi2);
    out << j.dump() << "\n";
    return r;
  }
  const auto& a = r.ate;
  const auto& p = r.rpe;
  const auto& o = m_params.evaluation;
  out << "ATE  " << a.pairs << " pairs (max_difference " << o.max_difference << " s, offset "
      << o.offset << " s)\n"
      << "     rmse " << fixed(a.rmse, 6) << " m  mean " << fixed(a.mean, 6) << "  median "
      << fixed(a.median, 6) << "  std " << fixed(a.std, 6) << "  min " << fixed(a.min, 6)
      << "  max " << fixed(a.max, 6) << "\n"
      << "RPE  " << p.pairs << " pairs (delta " << o.delta << " " << toString(o.delta_unit) << ")\n"
      << "     trans rmse " << fixed(p.trans_rmse, 6) << " m    mean " << fixed(p.trans_mean, 6)
      << "  median " << fixed(p.trans_median, 6) << "  max " << fixed(p.trans_max, 6) << "\n"
      << "     rot   rmse " << fixed(p.rot_rmse_deg, 6) << " deg  mean " << fixed(p.rot_mean_deg, 6)
      << "  median " << fixed(p.rot_median_deg, 6) << "  max " << fixed(p.rot_max_deg, 6) << "\n";
  if (m_edgeChi2)
    printEdges(out, *m_edgeChi2);
  return r;
}
}  // namespace roislam::evaluation
