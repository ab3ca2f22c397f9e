/* MRPT's graph-SLAM engine, CGraphSlamEngine<CNetworkOfPoses3DInf>, run
 * headless on observation-only RGB-D data, with MRPT 2.5.8's defects for
 * 3-D graphs worked around where they happen
 * (../shared/notes/mrpt-2.5-findings.md, Q2):
 *  - Key-press pause: the constructor does not recognise its own 3-D
 *    constraint class (it lists "CPose3DPDFGaussianInf", the class calls
 *    itself "mrpt::poses::CPose3DPDFGaussianInf"), warns that it is untested
 *    and waits for a key. create() runs it with stdin from /dev/null and its
 *    console output (that warning and prompt, notes that visuals and ground
 *    truth are off) into /dev/null; the engine keeps the messages in its log
 *    (getDescriptiveReport()).
 *  - Spanning-tree reset: after every step that registered a node, the engine
 *    recomputes every node pose from the edges of its Dijkstra spanning tree,
 *    after the optimiser ran, so the optimiser's work is lost before the next
 *    step's deciders or the caller see it. The poses are saved when the
 *    optimiser has run (monitorNodeRegistration(), called between it and the
 *    reset) and put back after the step.
 *  - No 3-D ground truth (its readers throw in 3-D): constructed without one;
 *    the caller evaluates against the TUM ground truth (CSlamRunner).
 *  - No 3-D map (computeMap() throws): never asked; CSlamOutputWriter builds
 *    map.bt from the keyframes' clouds.
 * The time table MRPT's time logger prints when the engine is destroyed is
 * not printed (it is in getDescriptiveReport()).
 */
#pragma once

// The decider headers rely on the global `using namespace std` that
// CNodeRegistrationDecider_impl.h introduces, so it must come first.
#include <mrpt/graphslam/interfaces/CNodeRegistrationDecider.h>
//
#include <mrpt/graphslam/CGraphSlamEngine.h>
#include <roislam/graphslam/CSlamContext.h>
#include <roislam/graphslam/TSlamDeciders.h>

#include <memory>
#include <string>

namespace roislam::graphslam
{
class CRgbdGraphSlamEngine : public mrpt::graphslam::CGraphSlamEngine<TGraph>
{
 public:
  /** The engine over `deciders` (which must outlive it), configured by
   *  `iniFile` (MRPT's [GeneralConfiguration] etc.; our deciders' parts are
   *  read by their loadParams(), called here). Errors propagate (MRPT adds
   *  its call stack after the first line). */
  static std::unique_ptr<CRgbdGraphSlamEngine> create(
      const std::string& iniFile, const TSlamDeciders& deciders);
  ~CRgbdGraphSlamEngine() override;

  /** One step on one observation (MRPT's observation-only rawlog format). */
  bool step(mrpt::obs::CObservation::Ptr observation);

  /** MRPT's report: edge counts, parameters, timings, the engine's log. */
  std::string descriptiveReport() const;

  /** The edge decider's and the optimiser's time in the last step, ms. */
  double lastBackendMs() const;
  /** The last time of one of the sections MRPT's engine times, ms:
   *  "edge_registrar", "optimizer" (every step), "dijkstra_nodes_estimation"
   *  (steps that registered a node); 0 for one never timed. */
  double lastSectionMs(const std::string& section) const;

  /** MRPT's step, then the optimised poses put back (see above). */
  bool _execGraphSlamStep(
      mrpt::obs::CActionCollection::Ptr& action, mrpt::obs::CSensoryFrame::Ptr& observations,
      mrpt::obs::CObservation::Ptr& observation, size_t& rawlog_entry) override;

 protected:
  /** MRPT's check; after the optimiser of a step that registered a node,
   *  also saves the poses the spanning-tree reset is about to replace. */
  void monitorNodeRegistration(bool registered, std::string class_name) override;

 private:
  CRgbdGraphSlamEngine(const std::string& iniFile, const TSlamDeciders& deciders);

  /** The node poses as the optimiser left them in this step. */
  TGraph::global_poses_t m_optimizedPoses;
  bool m_posesSaved = false;
  std::size_t m_entry = 0;
};
}  // namespace roislam::graphslam
