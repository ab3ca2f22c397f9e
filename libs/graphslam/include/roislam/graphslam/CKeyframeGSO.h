/* Graph optimiser for our deciders: full SPA Levenberg-Marquardt
 * (optimize_graph_spa_levmarq) of the keyframe graph, only on steps where a
 * loop closure was accepted (the graph between closures is a chain that
 * odometry already solves). MRPT 2.5's CEmptyGSO is abstract and CLevMarqGSO
 * ignores bursts of visual closures, hence this one. Note: CGraphSlamEngine
 * 2.5 re-derives node poses by Dijkstra after every step, so callers of the
 * engine re-optimise at the end (CSlamContext::optimize). Options: [GraphSlam]
 * optimizer_max_iterations.
 */
#pragma once

#include <mrpt/graphslam/interfaces/CGraphSlamOptimizer.h>
#include <roislam/graphslam/CSlamContext.h>

#include <memory>

namespace roislam::graphslam
{
class CKeyframeGSO : public mrpt::graphslam::optimizers::CGraphSlamOptimizer<TGraph>
{
 public:
  CKeyframeGSO() = default;
  explicit CKeyframeGSO(std::shared_ptr<CSlamContext> context) : m_context(std::move(context)) {}

  void setContext(std::shared_ptr<CSlamContext> context) { m_context = std::move(context); }

  bool updateState(
      mrpt::obs::CActionCollection::Ptr action, mrpt::obs::CSensoryFrame::Ptr observations,
      mrpt::obs::CObservation::Ptr observation) override;
  bool justFullyOptimizedGraph() const override { return m_justOptimized; }
  void loadParams(const std::string& iniFile) override {}
  void printParams() const override {}

  std::size_t optimizations() const { return m_optimizations; }

  static constexpr const char* kName = "CKeyframeGSO";
  static constexpr const char* kDescription =
      "Full SPA Levenberg-Marquardt of the keyframe graph after each accepted loop closure";

 protected:
  void optimizeGraph() override;

 private:
  std::shared_ptr<CSlamContext> m_context;
  std::size_t m_seenLoops = 0;
  std::size_t m_optimizations = 0;
  bool m_justOptimized = false;
};
}  // namespace roislam::graphslam
