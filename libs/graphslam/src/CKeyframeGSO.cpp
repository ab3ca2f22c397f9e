#include <roislam/graphslam/CKeyframeGSO.h>
#include <roislam/graphslam/SlamIni.h>

#include <Eigen/Dense>
#include <algorithm>
#include <iostream>
#include <sstream>
#include <stdexcept>

namespace roislam::graphslam
{
CSlamContext& CKeyframeGSO::ctx() const
{
  return sharedContext(m_context, kName);
}

void CKeyframeGSO::loadParams(const std::string& iniFile)
{
  m_params = loadDeciderParams(ctx(), iniFile, ESlamParams::Optimizer, kName);
}

void CKeyframeGSO::printParams() const
{
  std::cout << m_params << std::flush;
}

void CKeyframeGSO::getDescriptiveReport(std::string* report) const
{
  std::ostringstream ss;
  ss << kName << ": " << kDescription << "\n"
     << m_params << "optimisations " << m_optimizations << " (windowed " << m_windowedOptimizations
     << ")\n";
  *report = ss.str();
}

bool CKeyframeGSO::updateState(
    mrpt::obs::CActionCollection::Ptr, mrpt::obs::CSensoryFrame::Ptr, mrpt::obs::CObservation::Ptr)
{
  m_justOptimized = false;
  auto& c = ctx();
  // Closures are only added by the edge decider, earlier in this step (and
  // removed only by our optimisations): the new ones are at the end.
  if (c.loopClosures().size() > m_seenLoops)
    optimizeForClosures(m_seenLoops);
  m_seenLoops = c.loopClosures().size();
  return true;
}

double CKeyframeGSO::worstClosureError(std::size_t firstLoop) const
{
  double worst = 0;
  const auto& loops = ctx().loopClosures();
  const TGraph& g = *this->m_graph;
  for (std::size_t i = firstLoop; i < loops.size(); ++i)
  {
    const auto it = g.edges.find(loops[i].edge());
    if (it != g.edges.end())
      worst = std::max(worst, CSlamContext::edgeChi2(g, it));
  }
  return worst;
}

void CKeyframeGSO::optimizeForClosures(std::size_t firstNewLoop)
{
  // Optimise at once when a new closure disagrees with the current
  // estimate; consistent ones wait for a few more keyframes.
  const auto& opt = ctx().config().backEnd;
  ++m_pendingLoopKeyframes;
  // A whole-graph solve costs more the bigger the graph (on a 900-keyframe
  // run over one desk, 1.3-1.8 s): those are spaced by a number of
  // loop-closing keyframes that grows with the graph (nodes / 10).
  // Inconsistent closures are solved at once over the newest keyframes
  // only (optimize_window_keyframes), at a cost that stays flat; with
  // no window they solve the whole graph, every nodes / 50 keyframes.
  const std::size_t nodes = this->m_graph->nodes.size();
  const std::size_t every =
      std::max(static_cast<std::size_t>(opt.optimize_every_keyframes), nodes / 10);
  const auto window = static_cast<std::size_t>(opt.optimize_window_keyframes);
  const bool inconsistent =
      worstClosureError(firstNewLoop) > opt.optimize_min_chi2 * ctx().varianceFactor();
  if (m_pendingLoopKeyframes >= every ||
      (inconsistent && window == 0 &&
       m_pendingLoopKeyframes >= std::max<std::size_t>(1, nodes / 50)))
  {
    optimize(0);
    m_pendingLoopKeyframes = 0;
  }
  else if (inconsistent && window > 0)
  {
    // The pending count is kept: the window leaves older keyframes where
    // they were, the next whole-graph solve moves them.
    const auto r = optimize(window);
    if (r.freeNodes + 1 < nodes)
      ++m_windowedOptimizations;
    else
      m_pendingLoopKeyframes = 0;  // the window held the whole graph
  }
}

TOptimizationReport CKeyframeGSO::optimize(std::size_t window, bool measureChi2)
{
  auto& c = ctx();
  const auto report = c.optimize(*this->m_graph, window, measureChi2);
  c.correctFrontEnd(*this->m_graph);
  ++m_optimizations;
  m_justOptimized = window == 0 || report.freeNodes + 1 >= this->m_graph->nodes.size();
  return report;
}

void CKeyframeGSO::optimizeGraph()
{
  optimize(0);
}

TOptimizationReport CKeyframeGSO::finish()
{
  const auto r = optimize(0, true);
  m_seenLoops = ctx().loopClosures().size();
  return r;
}
}  // namespace roislam::graphslam
