#include <roislam/graphslam/CKeyframeERD.h>
#include <roislam/graphslam/CKeyframeGSO.h>
#include <roislam/graphslam/CKeyframeNRD.h>
#include <roislam/graphslam/TSlamDeciders.h>

namespace roislam::graphslam
{
CKeyframeNRD* TSlamDeciders::ourNode() const
{
  return dynamic_cast<CKeyframeNRD*>(node.get());
}

CKeyframeERD* TSlamDeciders::ourEdge() const
{
  return dynamic_cast<CKeyframeERD*>(edge.get());
}

CKeyframeGSO* TSlamDeciders::ourOptimizer() const
{
  return dynamic_cast<CKeyframeGSO*>(optimizer.get());
}
}  // namespace roislam::graphslam
