/* The timed part of one SLAM run, frame by frame: while frame i is tracked
 * and registered, frame i+1 is decoded on a second thread, which in ROI modes
 * also detects its ROI (CRgbdOdometry::detectRoiAhead), so stage 1 costs the
 * tracking thread nothing. Per frame: CKeyframeNRD (front end, new keyframe
 * node), CKeyframeERD (keyframe edges and verified loop closures), and an
 * SPA optimisation when a new closure disagrees with the current estimate
 * (over the newest keyframes only) or every few loop-closing keyframes (the
 * whole graph) ([GraphSlam] optimize_min_chi2, optimize_window_keyframes,
 * optimize_every_keyframes); finish() runs the final one.
 *
 * Drives our deciders directly rather than through CGraphSlamEngine, whose
 * 2.5 version resets optimised 3-D poses from the spanning tree after every
 * optimisation (../shared/notes/mrpt-2.5-findings.md).
 *
 * Used by CRoiGraphSlamApp (which writes the outputs) and by the paired
 * end-to-end speed benchmark (several pipelines stepped in turn on the same
 * sequence, so machine load hits every mode alike). Not thread-safe; the
 * source must outlive nothing: the pipeline owns it.
 */
#pragma once

#include <roislam/frontend/TFrameResult.h>
#include <roislam/graphslam/CKeyframeERD.h>
#include <roislam/graphslam/CKeyframeNRD.h>
#include <roislam/graphslam/CSlamContext.h>
#include <roislam/io/CFrameSource.h>
#include <roislam/io/TumTrajectory.h>

#include <future>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace roislam::graphslam
{
class CSlamPipeline
{
 public:
  /** What the pipeline keeps of each frame. */
  struct TFrameRecord
  {
    frontend::TFrameResult result;
    /** Edge registration, loop closures and optimisation, milliseconds. */
    double backendMs = 0;
  };

  /** Starts decoding the first frame at once. Throws std::invalid_argument on
   *  invalid options, like CSlamContext. */
  CSlamPipeline(const CSlamContext::TConfig& config, std::unique_ptr<io::CFrameSource> source);
  /** Waits for a pending decode. */
  ~CSlamPipeline();
  CSlamPipeline(const CSlamPipeline&) = delete;
  CSlamPipeline& operator=(const CSlamPipeline&) = delete;

  /** Processes the next frame; false (and nothing done) at the end of the
   *  sequence. Decoding errors of the source propagate. */
  bool step();

  /** Blocks until the next frame is decoded (and its ROI detected): the time
   *  the next step() would wait for it. For benchmarks that time steps of
   *  several pipelines in turn. */
  void waitForPrefetch() const
  {
    if (m_next.valid())
      m_next.wait();
  }

  /** Final optimisation (call once, after the last step). */
  TOptimizationReport finish();

  /** Every tracked frame (Lost ones have no pose): a keyframe's optimised
   *  node pose, other frames their reference keyframe's (+) their relative
   *  pose. */
  io::TTrajectory trajectory() const;
  /** A keyframe's optimised pose (its graph node), or the front end's when
   *  it has no node. Throws std::out_of_range on a bad id. */
  mrpt::poses::CPose3D keyframePose(std::size_t id) const;

  const std::vector<TFrameRecord>& records() const { return m_records; }
  /** Optimisations run so far (loop closures and finish()). */
  std::size_t optimizations() const { return m_optimizations; }
  /** Of those, the ones over the newest keyframes only. */
  std::size_t windowedOptimizations() const { return m_windowedOptimizations; }
  const CSlamContext& context() const { return *m_ctx; }
  const TGraph& graph() const { return m_graph; }
  const io::CFrameSource& source() const { return *m_source; }

 private:
  using TRoiHint = frontend::CRgbdOdometry::TRoiHint;
  using TFetched = std::pair<std::optional<io::TRGBDFrame>, std::optional<TRoiHint>>;
  void startFetch();

  std::unique_ptr<io::CFrameSource> m_source;
  std::shared_ptr<CSlamContext> m_ctx;
  TGraph m_graph;
  CKeyframeNRD m_nrd;
  CKeyframeERD m_erd;
  std::future<TFetched> m_next;
  std::vector<TFrameRecord> m_records;
  std::size_t m_optimizations = 0;
  std::size_t m_windowedOptimizations = 0;
  /** Keyframes that brought loop closures since the last optimisation. */
  std::size_t m_pendingLoopKeyframes = 0;
};
}  // namespace roislam::graphslam
