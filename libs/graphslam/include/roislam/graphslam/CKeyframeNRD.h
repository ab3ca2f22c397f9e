/* Node registration decider for 3-D RGB-D graph SLAM: one node per front-end
 * keyframe (node id == keyframe id). Each observation (a
 * CObservation3DRangeScan) is tracked by the shared context's CRgbdOdometry;
 * when it becomes a keyframe the node and the odometry edge from its reference
 * keyframe are added. MRPT 2.5 has no 3-D visual NRD; this is ours, run inside
 * mrpt::graphslam::CGraphSlamEngine (CRgbdGraphSlamEngine, by CSlamPipeline
 * for both roi-graphslam and roi-graphslam-engine), chosen by name through
 * CRoislamOptionsChecker::createDeciders(). The first registration adds the
 * root (keyframe 0) and keyframe 1, as the engine requires.
 *
 * Parameters (loadParams()): every [FrontEnd] key of TRgbdOdometryOptions.h, in
 * [NodeRegistrationDeciderParameters] in MRPT's layout, with the front end's
 * component sections ([RoiDetector], [FeatureExtractor], [FeatureMatcher]),
 * and the map and edge-weight keys of CSlamContext.h (map_decimation,
 * map_max_depth_m, edge_information, edge_sigma_m, edge_sigma_deg) in
 * [GeneralConfiguration] (SlamIni.h).
 * Note: MRPT's decider headers put `using namespace std` at global scope, so
 * include this header only where the deciders are needed.
 */
#pragma once

#include <mrpt/graphslam/interfaces/CNodeRegistrationDecider.h>
#include <roislam/frontend/TPreparedFrame.h>
#include <roislam/graphslam/CSlamContext.h>

#include <memory>
#include <optional>
#include <string>

namespace roislam::graphslam
{
class CKeyframeNRD : public mrpt::graphslam::deciders::CNodeRegistrationDecider<TGraph>
{
 public:
  CKeyframeNRD() = default;
  explicit CKeyframeNRD(std::shared_ptr<CSlamContext> context);

  /** The context shared with our edge decider and optimiser (required
   *  before updateState(); CRoislamOptionsChecker::createDeciders sets it). */
  void setContext(std::shared_ptr<CSlamContext> context);
  const std::shared_ptr<CSlamContext>& context() const { return m_context; }

  /** The frame of `observation`, already decoded and prepared
   *  (CRgbdOdometry::prepare) on another thread by CSlamPipeline:
   *  updateState(observation) tracks it instead of converting and preparing
   *  the observation itself (same result, the work done ahead). */
  void prepareAhead(const mrpt::obs::CObservation* observation, frontend::TPreparedFrame prepared);

  /** Tracks a CObservation3DRangeScan (other observations are ignored) and
   *  registers its node when it becomes a keyframe. */
  bool updateState(
      mrpt::obs::CActionCollection::Ptr action, mrpt::obs::CSensoryFrame::Ptr observations,
      mrpt::obs::CObservation::Ptr observation) override;

  /** Registers the node of a front-end result that made a new keyframe
   *  (and its odometry edge); returns true when a node was registered (true
   *  also for the first registration, which adds two). */
  bool registerFrame(const frontend::TFrameResult& result);

  /** Reads the parameters above from `iniFile` into the context, unless its
   *  creator configured it (CSlamContext::EConfigOrigin::Caller). Throws
   *  "ini <file>: ..." for a missing file, an unknown key or a bad value. */
  void loadParams(const std::string& iniFile) override;
  /** Prints the parameters in use to stdout (as MRPT's deciders do), ini
   *  text with the keys the ini does not set marked "(default)". */
  void printParams() const override;
  TGraph::global_pose_t getCurrentRobotPosEstimation() const override;
  /** Description, parameters and the front end's counters. */
  void getDescriptiveReport(std::string* report) const override;

  static constexpr const char* kName = "CKeyframeNRD";
  static constexpr const char* kDescription =
      "One node per RGB-D visual-odometry keyframe (roislam CRgbdOdometry: features + depth, "
      "3-D RANSAC, ROI modes, depth-ICP fallback); odometry edge from the reference keyframe";

 private:
  CSlamContext& ctx() const;

  std::shared_ptr<CSlamContext> m_context;
  /** describeSlamParams() text of the parameters loadParams() set. */
  std::string m_params;
  mrpt::poses::CPose3D m_currentPose;
  std::size_t m_observations = 0;
  const mrpt::obs::CObservation* m_aheadFor = nullptr;
  std::optional<frontend::TPreparedFrame> m_ahead;
};
}  // namespace roislam::graphslam
