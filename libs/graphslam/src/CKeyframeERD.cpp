#include <roislam/graphslam/CKeyframeERD.h>

#include <sstream>
#include <stdexcept>

namespace roislam::graphslam
{
CKeyframeERD::CKeyframeERD(std::shared_ptr<CSlamContext> context) : m_context(std::move(context)) {}

void CKeyframeERD::setContext(std::shared_ptr<CSlamContext> context)
{
  m_context = std::move(context);
}

std::shared_ptr<CSlamContext> CKeyframeERD::context() const
{
  if (m_context)
    return m_context;
  return this->m_graph ? CSlamContext::forGraph(this->m_graph) : nullptr;
}

CSlamContext& CKeyframeERD::ctx()
{
  auto c = context();
  if (!c)
    throw std::logic_error("CKeyframeERD: no graph and no context set");
  // The per-graph context lives in the registry; keep our own reference.
  return *c;
}

void CKeyframeERD::setGraphPtr(TGraph* graph)
{
  CEdgeRegistrationDecider<TGraph>::setGraphPtr(graph);
}

bool CKeyframeERD::updateState(
    mrpt::obs::CActionCollection::Ptr, mrpt::obs::CSensoryFrame::Ptr, mrpt::obs::CObservation::Ptr)
{
  this->m_just_inserted_lc = false;
  if (const auto& last = ctx().lastFrame())
    registerKeyframe(*last);
  return true;
}

CKeyframeERD::TEdgeReport CKeyframeERD::registerKeyframe(const frontend::TFrameResult& r)
{
  this->m_just_inserted_lc = false;
  TEdgeReport rep;
  if (!r.isNewKeyframe || r.newKeyframeId == 0 || !this->m_graph->nodes.count(r.newKeyframeId))
    return rep;
  auto& c = ctx();
  // Recent-keyframe constraints measured by the front end (the first one is
  // the odometry edge the NRD added).
  for (std::size_t i = 1; i < r.constraints.size(); ++i)
  {
    const auto& k = r.constraints[i];
    this->m_graph->insertEdgeAtEnd(
        static_cast<mrpt::graphs::TNodeID>(k.fromKeyframe),
        static_cast<mrpt::graphs::TNodeID>(k.toKeyframe),
        mrpt::poses::CPose3DPDFGaussianInf(
            k.relativePose, c.edgeInformation(k.information, k.method, k.inliers)));
    ++rep.recentEdges;
    ++m_stats["recent"];
  }
  addLoopClosures(r.newKeyframeId, rep);
  return rep;
}

void CKeyframeERD::addLoopClosures(std::size_t id, TEdgeReport& rep)
{
  auto& c = ctx();
  auto& g = *this->m_graph;
  const auto& opt = c.config().backEnd;
  const auto recalled = c.observeLandmarks(id);
  const auto candidates = c.loopCandidates(id, recalled, g);
  rep.loopCandidates = candidates.size();
  for (const auto& [cand, source] : candidates)
  {
    const auto est = c.odometry().registerKeyframes(cand, id);
    if (!est || est->inliers < static_cast<std::size_t>(opt.loop_min_inliers))
      continue;
    // Sanity against the current estimate: drift over a loop is bounded (by
    // a share of the path around it), a wrong association usually is not.
    const auto itA = g.nodes.find(cand), itB = g.nodes.find(id);
    if (itA == g.nodes.end() || itB == g.nodes.end())
      continue;
    const mrpt::poses::CPose3D predicted = itB->second - itA->second;
    if ((predicted.translation() - est->pose.translation()).norm() >
        c.loopDiscrepancyLimit(cand, id, g))
      continue;
    g.insertEdgeAtEnd(
        static_cast<mrpt::graphs::TNodeID>(cand), static_cast<mrpt::graphs::TNodeID>(id),
        mrpt::poses::CPose3DPDFGaussianInf(
            est->pose, c.edgeInformation(
                           est->information, frontend::ETrackingMethod::Features, est->inliers)));
    TLoopClosure lc;
    lc.fromKeyframe = cand;
    lc.toKeyframe = id;
    lc.source = source;
    lc.inliers = est->inliers;
    c.addLoopClosure(lc);
    ++rep.loopClosures;
    ++m_stats[source == ELoopSource::Landmark ? "loop_landmark" : "loop_proximity"];
    this->m_just_inserted_lc = true;
  }
}

void CKeyframeERD::getEdgesStats(std::map<std::string, int>* edgeTypeToNum) const
{
  // CGraphSlamEngine only accepts its own edge-type names ("lc" and
  // "Odometry"/"ICP2D"/"ICP3D"); the detailed counts are in edgeCounts().
  if (!edgeTypeToNum)
    return;
  edgeTypeToNum->clear();
  const auto get = [&](const char* k)
  {
    const auto it = m_stats.find(k);
    return it == m_stats.end() ? 0 : it->second;
  };
  (*edgeTypeToNum)["lc"] = get("loop_landmark") + get("loop_proximity");
  (*edgeTypeToNum)["Odometry"] = get("recent");
}

void CKeyframeERD::getDescriptiveReport(std::string* report) const
{
  std::ostringstream ss;
  ss << kName << ": " << kDescription << "\n";
  for (const auto& [k, n] : m_stats)
    ss << k << ": " << n << "\n";
  *report = ss.str();
}
}  // namespace roislam::graphslam
