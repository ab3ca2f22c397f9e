/* Node registration decider for 3-D RGB-D graph SLAM: one node per front-end
 * keyframe (node id == keyframe id). Each observation (a
 * CObservation3DRangeScan) is tracked by the shared context's CRgbdOdometry;
 * when it becomes a keyframe the node and the odometry edge from its reference
 * keyframe are added. MRPT 2.5 has no 3-D visual NRD; this is ours, usable
 * inside mrpt::graphslam::CGraphSlamEngine (registered by name in
 * CRoislamOptionsChecker: updateState() runs the front end on the
 * observation) or fed front-end results through registerFrame() by
 * CSlamPipeline, which runs the front end itself. The first registration adds
 * the root (keyframe 0) and keyframe 1, as the engine requires.
 *
 * No ini keys of its own: loadParams(file) loads the whole configuration
 * (CSlamContext::loadConfig) into a new shared context for this graph, when
 * no context was given explicitly.
 * Note: MRPT's decider headers put `using namespace std` at global scope, so
 * include this header only where the deciders are needed.
 */
#pragma once

#include <mrpt/graphslam/interfaces/CNodeRegistrationDecider.h>
#include <roislam/graphslam/CSlamContext.h>

#include <memory>

namespace roislam::graphslam
{
class CKeyframeNRD : public mrpt::graphslam::deciders::CNodeRegistrationDecider<TGraph>
{
 public:
  CKeyframeNRD() = default;
  explicit CKeyframeNRD(std::shared_ptr<CSlamContext> context);

  /** Uses this context instead of the per-graph shared one. */
  void setContext(std::shared_ptr<CSlamContext> context);
  /** The context in use (the per-graph one once a graph is set). */
  std::shared_ptr<CSlamContext> context() const;

  bool updateState(
      mrpt::obs::CActionCollection::Ptr action, mrpt::obs::CSensoryFrame::Ptr observations,
      mrpt::obs::CObservation::Ptr observation) override;

  /** Registers the node of a front-end result that made a new keyframe
   *  (and its odometry edge); returns true when a node was registered (true
   *  also for the first registration, which adds two). */
  bool registerFrame(const frontend::TFrameResult& result);

  void setGraphPtr(TGraph* graph) override;
  void loadParams(const std::string& iniFile) override;
  void printParams() const override {}
  TGraph::global_pose_t getCurrentRobotPosEstimation() const override;
  void getDescriptiveReport(std::string* report) const override;

  static constexpr const char* kName = "CKeyframeNRD";
  static constexpr const char* kDescription =
      "One node per RGB-D visual-odometry keyframe (roislam CRgbdOdometry: features + depth, "
      "3-D RANSAC, ROI modes, depth-ICP fallback); odometry edge from the reference keyframe";

 private:
  std::shared_ptr<CSlamContext> m_context;
  bool m_explicitContext = false;
  mrpt::poses::CPose3D m_currentPose;
  std::size_t m_observations = 0;
};
}  // namespace roislam::graphslam
