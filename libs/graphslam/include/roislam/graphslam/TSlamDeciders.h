/* The node and edge registration deciders and the optimiser of one graph-SLAM
 * run, as CRoislamOptionsChecker::createDeciders() builds them by name, and
 * the CSlamContext ours share. Owned here: MRPT's engine only points to them,
 * so destroy the engine first (CSlamPipeline does). Nothing of the run lives
 * anywhere else.
 */
#pragma once

// The decider headers rely on the global `using namespace std` that
// CNodeRegistrationDecider_impl.h introduces, so it must come first.
#include <mrpt/graphslam/interfaces/CNodeRegistrationDecider.h>
//
#include <mrpt/graphslam/interfaces/CEdgeRegistrationDecider.h>
#include <mrpt/graphslam/interfaces/CGraphSlamOptimizer.h>
#include <roislam/graphslam/CSlamContext.h>

#include <memory>
#include <string>

namespace roislam::graphslam
{
class CKeyframeNRD;
class CKeyframeERD;
class CKeyframeGSO;

struct TSlamDeciders
{
  /** Class names as MRPT's graphslam-engine takes them (-n, -e, -o). */
  struct TNames
  {
    std::string node = "CKeyframeNRD";
    std::string edge = "CKeyframeERD";
    std::string optimizer = "CKeyframeGSO";
  };

  TNames names;
  std::unique_ptr<mrpt::graphslam::deciders::CNodeRegistrationDecider<TGraph>> node;
  std::unique_ptr<mrpt::graphslam::deciders::CEdgeRegistrationDecider<TGraph>> edge;
  std::unique_ptr<mrpt::graphslam::optimizers::CGraphSlamOptimizer<TGraph>> optimizer;
  /** Shared by those of the three that are ours. */
  std::shared_ptr<CSlamContext> context;

  /** Ours among them, or null when MRPT's was chosen. */
  CKeyframeNRD* ourNode() const;
  CKeyframeERD* ourEdge() const;
  CKeyframeGSO* ourOptimizer() const;
};
}  // namespace roislam::graphslam
