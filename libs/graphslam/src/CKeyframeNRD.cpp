#include <mrpt/obs/CObservation3DRangeScan.h>
#include <roislam/graphslam/CKeyframeNRD.h>
#include <roislam/graphslam/SlamIni.h>
#include <roislam/io/ObservationConversion.h>

#include <iostream>
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
}

CSlamContext& CKeyframeNRD::ctx() const
{
  return sharedContext(m_context, kName);
}

void CKeyframeNRD::loadParams(const std::string& iniFile)
{
  m_params = loadDeciderParams(ctx(), iniFile, ESlamParams::NodeRegistration, kName);
}

void CKeyframeNRD::printParams() const
{
  std::cout << m_params << std::flush;
}

void CKeyframeNRD::prepareAhead(
    const mrpt::obs::CObservation* observation, frontend::TPreparedFrame prepared)
{
  m_aheadFor = observation;
  m_ahead = std::move(prepared);
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
  auto& c = ctx();
  std::optional<frontend::TPreparedFrame> prepared;
  if (m_ahead && m_aheadFor == scan.get())
    prepared = std::move(m_ahead);
  m_ahead.reset();
  m_aheadFor = nullptr;
  if (!prepared)
  {
    scan->load();
    auto frame =
        io::observationToFrame(*scan, "CKeyframeNRD observation " + std::to_string(m_observations));
    scan->unload();
    // Observations carry no sequence index; number them in arrival order.
    frame.index = m_observations;
    prepared = c.odometry().prepare(frame);
  }
  ++m_observations;
  const frontend::TFrameResult result = c.odometry().process(*prepared);
  c.recordFrame(result, prepared->frame);
  return registerFrame(result);
}

bool CKeyframeNRD::registerFrame(const frontend::TFrameResult& r)
{
  auto& c = ctx();
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
    g.nodes[0] = c.odometry().keyframe(0).pose;
  }
  g.nodes[id] = *r.pose;
  const auto& k = r.constraints.front();
  g.insertEdgeAtEnd(
      static_cast<mrpt::graphs::TNodeID>(k.fromKeyframe), id,
      mrpt::poses::CPose3DPDFGaussianInf(
          k.relativePose,
          c.edgeInformation(k.information, k.method, k.inliers, k.edgeInformation)));
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
  ss << kName << ": " << kDescription << "\n" << m_params;
  if (m_context)
  {
    const auto& s = m_context->odometry().stats();
    ss << "frames " << s.frames << ", keyframes " << s.keyframes << ", lost " << s.lost
       << ", anchors alone (flow) " << s.flow << ", fallback to the whole image "
       << s.fullImageFallback << ", depth ICP " << s.depthIcp << ", constant velocity "
       << s.constantVelocity << "\n";
  }
  *report = ss.str();
}
}  // namespace roislam::graphslam
