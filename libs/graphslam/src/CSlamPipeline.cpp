#include "roislam/graphslam/CSlamPipeline.h"

#include <mrpt/system/CTicTac.h>

// getEdgeSquareError() needs Eigen complete; MRPT's headers do not include it.
#include <Eigen/Dense>
#include <algorithm>
#include <stdexcept>

namespace roislam::graphslam
{
CSlamPipeline::CSlamPipeline(
    const CSlamContext::TConfig& config, std::unique_ptr<io::CFrameSource> source)
    : m_source(std::move(source)),
      m_ctx(std::make_shared<CSlamContext>(config)),
      m_nrd(m_ctx),
      m_erd(m_ctx)
{
  if (!m_source)
    throw std::invalid_argument("CSlamPipeline: no frame source");
  m_nrd.setGraphPtr(&m_graph);
  m_erd.setGraphPtr(&m_graph);
  m_records.reserve(m_source->size());
  // Only const members of the odometry are used on the prefetch thread
  // (prepare(): checks, grey image, stage 1), while step() runs process() on
  // the caller's.
  const frontend::CRgbdOdometry& odo = m_ctx->odometry();
  m_prefetch = std::make_unique<io::CFramePrefetcher<frontend::TPreparedFrame>>(
      *m_source, 1, [&odo](const io::TRGBDFrame& f) { return odo.prepare(f); });
}

CSlamPipeline::~CSlamPipeline()
{
  // The prefetch thread uses the source and the context: stop it first.
  m_prefetch.reset();
}

bool CSlamPipeline::step()
{
  const auto item = m_prefetch->next();
  if (!item)
    return false;
  const frontend::TPreparedFrame& prepared = item->prepared;

  // Front end, then the back end with its result; the back end's correction
  // comes back once, after an optimisation (optimize()).
  TFrameRecord rec;
  rec.result = m_ctx->odometry().process(prepared);
  m_ctx->recordFrame(rec.result, prepared.frame);
  const bool registered = m_nrd.registerFrame(rec.result);
  mrpt::system::CTicTac be;
  if (registered)
  {
    const std::size_t loopsBefore = m_ctx->loopClosures().size();
    if (m_erd.registerKeyframe(rec.result).loopClosures > 0)
      optimizeForClosures(loopsBefore);
  }
  rec.backendMs = be.Tac() * 1e3;
  m_records.push_back(std::move(rec));
  return true;
}

double CSlamPipeline::worstClosureError(std::size_t firstLoop) const
{
  double worst = 0;
  const auto& loops = m_ctx->loopClosures();
  for (std::size_t i = firstLoop; i < loops.size(); ++i)
  {
    const auto it = m_graph.edges.find(std::make_pair(
        static_cast<mrpt::graphs::TNodeID>(loops[i].fromKeyframe),
        static_cast<mrpt::graphs::TNodeID>(loops[i].toKeyframe)));
    if (it != m_graph.edges.end())
      worst = std::max(worst, m_graph.getEdgeSquareError(it, false));
  }
  return worst;
}

void CSlamPipeline::optimizeForClosures(std::size_t firstNewLoop)
{
  // Optimise at once when a new closure disagrees with the current
  // estimate; consistent ones wait for a few more keyframes.
  const auto& opt = m_ctx->config().backEnd;
  ++m_pendingLoopKeyframes;
  // A whole-graph solve costs more the bigger the graph (on a 900-keyframe
  // run over one desk, 1.3-1.8 s): those are spaced by a number of
  // loop-closing keyframes that grows with the graph (nodes / 10).
  // Inconsistent closures are solved at once over the newest keyframes
  // only (optimize_window_keyframes), at a cost that stays flat; with
  // no window they solve the whole graph, every nodes / 50 keyframes.
  const std::size_t nodes = m_graph.nodes.size();
  const std::size_t every =
      std::max(static_cast<std::size_t>(opt.optimize_every_keyframes), nodes / 10);
  const auto window = static_cast<std::size_t>(opt.optimize_window_keyframes);
  const bool inconsistent = worstClosureError(firstNewLoop) > opt.optimize_min_chi2;
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

TOptimizationReport CSlamPipeline::optimize(std::size_t window)
{
  const auto report = m_ctx->optimize(m_graph, window);
  m_ctx->correctFrontEnd(m_graph);
  ++m_optimizations;
  return report;
}

TOptimizationReport CSlamPipeline::finish()
{
  return optimize(0);
}
mrpt::poses::CPose3D CSlamPipeline::keyframePose(std::size_t id) const
{
  const auto it = m_graph.nodes.find(id);
  return it != m_graph.nodes.end() ? it->second : m_ctx->odometry().keyframe(id).pose;
}

io::TTrajectory CSlamPipeline::trajectory() const
{
  io::TTrajectory estimate;
  for (const auto& r : m_records)
  {
    const auto& fr = r.result;
    if (!fr.pose)
      continue;
    io::TPoseStamped p;
    p.timestamp = fr.timestamp;
    p.pose = fr.isNewKeyframe ? keyframePose(fr.newKeyframeId)
                              : keyframePose(fr.referenceKeyframe) + fr.relativePose;
    estimate.push_back(p);
  }
  return estimate;
}
}  // namespace roislam::graphslam
