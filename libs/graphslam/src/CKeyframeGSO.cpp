#include <roislam/graphslam/CKeyframeGSO.h>

namespace roislam::graphslam
{
bool CKeyframeGSO::updateState(
    mrpt::obs::CActionCollection::Ptr, mrpt::obs::CSensoryFrame::Ptr, mrpt::obs::CObservation::Ptr)
{
  m_justOptimized = false;
  if (!m_context && this->m_graph)
    m_context = CSlamContext::forGraph(this->m_graph);
  if (!m_context)
    return false;
  const auto loops = m_context->loopClosures().size();
  if (loops > m_seenLoops)
  {
    m_seenLoops = loops;
    optimizeGraph();
  }
  return true;
}

void CKeyframeGSO::optimizeGraph()
{
  if (!m_context || !this->m_graph)
    return;
  m_context->optimize(*this->m_graph);
  m_context->correctFrontEnd(*this->m_graph);
  ++m_optimizations;
  m_justOptimized = true;
}
}  // namespace roislam::graphslam
