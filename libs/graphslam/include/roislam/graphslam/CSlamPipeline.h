/* The timed part of one SLAM run, frame by frame: while frame i is tracked
 * and registered, frame i+1 is decoded on a second thread, which also
 * prepares it for the front end (CRgbdOdometry::prepare: grey image and, in
 * ROI modes, stage 1), so stage 1 costs the tracking thread nothing. Per
 * frame, in one direction: the front end (CRgbdOdometry::process) -> its
 * result to CKeyframeNRD (new keyframe node and odometry edge) and
 * CKeyframeERD (keyframe edges and verified loop closures) -> an SPA
 * optimisation when a new closure disagrees with the current estimate (over
 * the newest keyframes only) or every few loop-closing keyframes (the whole
 * graph) ([GraphSlam] optimize_min_chi2, optimize_window_keyframes,
 * optimize_every_keyframes), whose poses go back to the front end in one call
 * (CSlamContext::correctFrontEnd); finish() runs the final one.
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
#include <roislam/frontend/TPreparedFrame.h>
#include <roislam/graphslam/CKeyframeERD.h>
#include <roislam/graphslam/CKeyframeNRD.h>
#include <roislam/graphslam/CSlamContext.h>
#include <roislam/io/CFramePrefetcher.h>
#include <roislam/io/CFrameSource.h>
#include <roislam/io/TumTrajectory.h>

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
  void waitForPrefetch() const { m_prefetch->waitReady(); }

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
  /** The optimisation schedule after a keyframe that brought closures
   *  (those from index firstNewLoop of the context's loopClosures()). */
  void optimizeForClosures(std::size_t firstNewLoop);
  /** Largest squared error of the closures from index firstLoop on. */
  double worstClosureError(std::size_t firstLoop) const;
  /** Optimises (window 0 = whole graph) and corrects the front end. */
  TOptimizationReport optimize(std::size_t window);

  std::unique_ptr<io::CFrameSource> m_source;
  std::shared_ptr<CSlamContext> m_ctx;
  TGraph m_graph;
  CKeyframeNRD m_nrd;
  CKeyframeERD m_erd;
  std::vector<TFrameRecord> m_records;
  std::size_t m_optimizations = 0;
  std::size_t m_windowedOptimizations = 0;
  /** Keyframes that brought loop closures since the last optimisation. */
  std::size_t m_pendingLoopKeyframes = 0;
  /** Decodes and prepares frame i+1 while i is processed (last: it reads
   *  the source and the context, and stops before they go). */
  std::unique_ptr<io::CFramePrefetcher<frontend::TPreparedFrame>> m_prefetch;
};
}  // namespace roislam::graphslam
