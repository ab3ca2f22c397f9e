/* Edge registration decider for 3-D RGB-D graph SLAM, companion of
 * CKeyframeNRD (they share a CSlamContext). For each new keyframe node it
 * adds (1) the front end's constraints from the other recent keyframes and
 * (2) loop closures: candidates from ROI landmark recall (CLandmarkDatabase)
 * and from spatial proximity in the current estimate (older than
 * [GraphSlam] loop_min_keyframe_gap keyframes), each verified by 3-D RANSAC
 * between keyframes (CRgbdOdometry::registerKeyframes) and rejected when it
 * has too few inliers or disagrees with the estimate by more than
 * loop_max_discrepancy_m. Used inside CGraphSlamEngine or directly by
 * CRoiGraphSlamApp. Options: [GraphSlam] of CSlamContext.
 */
#pragma once

#include <mrpt/graphslam/interfaces/CEdgeRegistrationDecider.h>
#include <roislam/graphslam/CSlamContext.h>

#include <memory>

namespace roislam::graphslam
{
class CKeyframeERD : public mrpt::graphslam::deciders::CEdgeRegistrationDecider<TGraph>
{
 public:
  /** What registerKeyframe() added. */
  struct TEdgeReport
  {
    std::size_t recentEdges = 0;
    std::size_t loopCandidates = 0;
    std::size_t loopClosures = 0;
  };

  CKeyframeERD() = default;
  explicit CKeyframeERD(std::shared_ptr<CSlamContext> context);

  void setContext(std::shared_ptr<CSlamContext> context);
  std::shared_ptr<CSlamContext> context() const;

  /** Inside MRPT's engine: adds the edges of the node the NRD registered in
   *  this step, if any (the context's lastFrame()). */
  bool updateState(
      mrpt::obs::CActionCollection::Ptr action, mrpt::obs::CSensoryFrame::Ptr observations,
      mrpt::obs::CObservation::Ptr observation) override;

  /** Adds the edges of a front-end result that made a new keyframe whose
   *  node is in the graph (CKeyframeNRD::registerFrame): the front end's
   *  constraints from the other recent keyframes, then verified loop
   *  closures. Nothing for other results. */
  TEdgeReport registerKeyframe(const frontend::TFrameResult& result);

  void setGraphPtr(TGraph* graph) override;
  void loadParams(const std::string& iniFile) override {}
  void printParams() const override {}
  /** For the engine: {"lc": loop closures, "Odometry": recent-keyframe edges}. */
  void getEdgesStats(std::map<std::string, int>* edgeTypeToNum) const override;
  /** Edges added by kind: "recent", "loop_landmark", "loop_proximity". */
  const std::map<std::string, int>& edgeCounts() const { return m_stats; }
  void getDescriptiveReport(std::string* report) const override;

  static constexpr const char* kName = "CKeyframeERD";
  static constexpr const char* kDescription =
      "Recent-keyframe edges and loop closures from ROI landmark recall and spatial proximity, "
      "verified by 3-D RANSAC between keyframes";

 private:
  CSlamContext& ctx();
  /** Verifies the candidates of keyframe `id` and adds the accepted closures. */
  void addLoopClosures(std::size_t id, TEdgeReport& rep);
  std::shared_ptr<CSlamContext> m_context;
  std::map<std::string, int> m_stats;
};
}  // namespace roislam::graphslam
