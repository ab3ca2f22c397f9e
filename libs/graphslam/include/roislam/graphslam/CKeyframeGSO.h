/* Graph optimiser for our deciders: SPA Levenberg-Marquardt
 * (CSlamContext::optimize) of the keyframe graph on a schedule, after the
 * steps in which CKeyframeERD accepted loop closures, and the one correction
 * of the front end after each optimisation (CSlamContext::correctFrontEnd).
 *
 * The schedule: a keyframe whose new closure disagrees with the current
 * estimate (squared error > optimize_min_chi2) is optimised at once, over the
 * newest optimize_window_keyframes keyframes only (older ones held fixed, so
 * the cost stays flat); the whole graph is solved every
 * max(optimize_every_keyframes, nodes / 10) loop-closing keyframes (with no
 * window: inconsistent closures every nodes / 50) and once more at the end
 * (finish()). MRPT 2.5's CEmptyGSO is abstract and CLevMarqGSO ignores bursts
 * of visual closures (it skips closures after two consecutive ones), hence
 * this one.
 *
 * Parameters (loadParams()): optimizer_max_iterations, loop_outlier_chi2,
 * optimize_min_chi2, optimize_every_keyframes, optimize_window_keyframes of
 * CSlamContext.h, in [OptimizerParameters] in MRPT's layout (SlamIni.h).
 * Note: CGraphSlamEngine 2.5 resets every node pose to its spanning-tree
 * estimate after the optimiser has run; CRgbdGraphSlamEngine puts the
 * optimised poses back.
 */
#pragma once

#include <mrpt/graphslam/interfaces/CGraphSlamOptimizer.h>
#include <roislam/graphslam/CSlamContext.h>

#include <memory>
#include <string>

namespace roislam::graphslam
{
class CKeyframeGSO : public mrpt::graphslam::optimizers::CGraphSlamOptimizer<TGraph>
{
 public:
  CKeyframeGSO() = default;
  explicit CKeyframeGSO(std::shared_ptr<CSlamContext> context) : m_context(std::move(context)) {}

  /** The context shared with our deciders (required before updateState()). */
  void setContext(std::shared_ptr<CSlamContext> context) { m_context = std::move(context); }
  const std::shared_ptr<CSlamContext>& context() const { return m_context; }

  /** The schedule above, after the step's new loop closures (if any). */
  bool updateState(
      mrpt::obs::CActionCollection::Ptr action, mrpt::obs::CSensoryFrame::Ptr observations,
      mrpt::obs::CObservation::Ptr observation) override;
  /** The final whole-graph optimisation, after the last step. */
  TOptimizationReport finish();
  bool justFullyOptimizedGraph() const override { return m_justOptimized; }

  /** Reads the parameters above from `iniFile` into the context, unless its
   *  creator configured it. Throws "ini <file>: ..." on errors. */
  void loadParams(const std::string& iniFile) override;
  /** The parameters in use, to stdout (see CKeyframeNRD::printParams()). */
  void printParams() const override;
  /** Description, parameters and the optimisations run. */
  void getDescriptiveReport(std::string* report) const override;

  /** Optimisations run so far (loop closures and finish()). */
  std::size_t optimizations() const { return m_optimizations; }
  /** Of those, the ones over the newest keyframes only. */
  std::size_t windowedOptimizations() const { return m_windowedOptimizations; }

  static constexpr const char* kName = "CKeyframeGSO";
  static constexpr const char* kDescription =
      "SPA Levenberg-Marquardt of the keyframe graph after loop closures (windowed at once for "
      "inconsistent ones, whole graph every few loop-closing keyframes and at the end); "
      "corrects the front end's keyframes";

 protected:
  /** MRPT's interface: a whole-graph optimisation. */
  void optimizeGraph() override;

 private:
  CSlamContext& ctx() const;
  /** The schedule after a keyframe that brought closures (those from index
   *  firstNewLoop of the context's loopClosures()). */
  void optimizeForClosures(std::size_t firstNewLoop);
  /** Largest squared error of the closures from index firstLoop on. */
  double worstClosureError(std::size_t firstLoop) const;
  /** Optimises (window 0 = whole graph) and corrects the front end; the
   *  whole graph's chi2 only with measureChi2 (finish()). */
  TOptimizationReport optimize(std::size_t window, bool measureChi2 = false);

  std::shared_ptr<CSlamContext> m_context;
  std::string m_params;
  /** Closures in the context when the last step ended. */
  std::size_t m_seenLoops = 0;
  /** Keyframes that brought loop closures since the last whole-graph solve. */
  std::size_t m_pendingLoopKeyframes = 0;
  std::size_t m_optimizations = 0;
  std::size_t m_windowedOptimizations = 0;
  bool m_justOptimized = false;
};
}  // namespace roislam::graphslam
