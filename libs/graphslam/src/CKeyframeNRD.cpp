#include <mrpt/obs/CObservation3DRangeScan.h>
#include <roislam/common/CStrictIniFile.h>
#include <roislam/graphslam/CKeyframeNRD.h>
#include <roislam/io/ObservationConversion.h>

#include <sstream>
#include <stdexcept>

namespace roislam::graphslam
{
CKeyframeNRD::CKeyframeNRD(std::shared_ptr<CSlamContext> context)
{
  setContext(std::move(context));
}

void CKeyframeNRD::setContext(std::shared_ptr<CSlamContext> context)
{
  m_context = std::move(context);
  m_explicitContext = static_cast<bool>(m_context);
}

std::shared_ptr<CSlamContext> CKeyframeNRD::context() const
{
  if (m_context)
    return m_context;
  return this->m_graph ? CSlamContext::forGraph(this->m_graph) : nullptr;
}

void CKeyframeNRD::setGraphPtr(TGraph* graph)
{
  CNodeRegistrationDecider<TGraph>::setGraphPtr(graph);
  if (!m_explicitContext)
    m_context.reset();  // looked up per graph in context()
}

void CKeyframeNRD::loadParams(const std::string& iniFile)
{
  if (m_explicitContext || iniFile.empty())
    return;
  const common::CStrictIniFile cfg(iniFile);
  auto ctx = std::make_shared<CSlamContext>(CSlamContext::loadConfig(cfg, iniFile));
  if (this->m_graph)
    CSlamContext::setForGraph(this->m_graph, ctx);
  else
    m_context = ctx;
}

bool CKeyframeNRD::updateState(
    mrpt::obs::CActionCollection::Ptr, mrpt::obs::CSensoryFrame::Ptr observations,
    mrpt::obs::CObservation::Ptr observation)
{
  mrpt::obs::CObservation3DRangeScan::Ptr scan;
  if (observation)
    scan = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(observation);
  else if (observations)
    scan = observations->getObservationByClass<mrpt::obs::CObservation3DRangeScan>();
  if (!scan)
    return false;  // other sensors carry nothing for us
  scan->load();
  auto frame =
      io::observationToFrame(*scan, "CKeyframeNRD observation " + std::to_string(m_observations));
  scan->unload();
  // Observations carry no sequence index; number them in arrival order.
  frame.index = m_observations++;
  auto ctx = context();
  if (!ctx)
    throw std::logic_error("CKeyframeNRD: no graph and no context set");
  const frontend::TFrameResult result = ctx->odometry().process(frame);
  ctx->recordFrame(result, frame);
  return registerFrame(result);
}

bool CKeyframeNRD::registerFrame(const frontend::TFrameResult& r)
{
  auto ctx = context();
  if (!ctx)
    throw std::logic_error("CKeyframeNRD: no graph and no context set");
  if (r.pose)
    m_currentPose = *r.pose;
  if (!r.isNewKeyframe || r.newKeyframeId == 0)
    return false;
  if (r.constraints.empty())
    throw std::logic_error("CKeyframeNRD: a new keyframe without its odometry constraint");

  auto& g = *this->m_graph;
  const auto id = static_cast<mrpt::graphs::TNodeID>(r.newKeyframeId);
  if (g.nodes.empty())
  {
    // First registration: root (keyframe 0) and keyframe 1 together, as
    // CGraphSlamEngine expects.
    g.root = 0;
    g.nodes[0] = ctx->odometry().keyframe(0).pose;
  }
  g.nodes[id] = *r.pose;
  const auto& c = r.constraints.front();
  g.insertEdgeAtEnd(
      static_cast<mrpt::graphs::TNodeID>(c.fromKeyframe), id,
      mrpt::poses::CPose3DPDFGaussianInf(
          c.relativePose, ctx->edgeInformation(c.information, c.method, c.inliers)));
  this->m_prev_registered_nodeID = id;
  return true;
}

TGraph::global_pose_t CKeyframeNRD::getCurrentRobotPosEstimation() const
{
  return TGraph::global_pose_t(m_currentPose);
}

void CKeyframeNRD::getDescriptiveReport(std::string* report) const
{
  std::ostringstream ss;
  ss << kName << ": " << kDescription << "\n";
  if (auto ctx = context())
  {
    const auto& s = ctx->odometry().stats();
    ss << "frames " << s.frames << ", keyframes " << s.keyframes << ", lost " << s.lost << "\n";
  }
  *report = ss.str();
}
}  // namespace roislam::graphslam
