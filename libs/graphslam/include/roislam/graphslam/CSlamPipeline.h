/* The timed part of one SLAM run, frame by frame, through MRPT's graph-SLAM
 * engine (CRgbdGraphSlamEngine, i.e. CGraphSlamEngine<CNetworkOfPoses3DInf>)
 * with the deciders and optimiser of TSlamDeciders: the one code path of
 * roi-graphslam (our three, configured by its ini and command line) and of
 * roi-graphslam-engine (chosen by name, configured by their loadParams()).
 *
 * While frame i is tracked and registered, frame i+1 is decoded on a second
 * thread, which also prepares it for the front end (CRgbdOdometry::prepare:
 * grey image and, in ROI modes, stage 1) and converts it to the
 * CObservation3DRangeScan the engine steps on, so neither costs the tracking
 * thread anything (CKeyframeNRD::prepareAhead()). Per step, in one direction:
 * CKeyframeNRD (the front end, CRgbdOdometry::process, and the new keyframe's
 * node and odometry edge) -> the edge decider (CKeyframeERD: keyframe edges
 * and verified loop closures) -> the optimiser (CKeyframeGSO: its schedule,
 * whose poses go back to the front end in one call,
 * CSlamContext::correctFrontEnd); finish() runs the final optimisation.
 *
 * Also used by the paired end-to-end speed benchmark (several pipelines
 * stepped in turn on the same sequence, so machine load hits every mode
 * alike). Not thread-safe; the pipeline owns the source.
 */
#pragma once

#include <roislam/frontend/TFrameResult.h>
#include <roislam/frontend/TPreparedFrame.h>
#include <roislam/graphslam/CRgbdGraphSlamEngine.h>
#include <roislam/graphslam/CSlamContext.h>
#include <roislam/graphslam/CSlamObserver.h>
#include <roislam/graphslam/TSlamDeciders.h>
#include <roislam/io/CFramePrefetcher.h>
#include <roislam/io/CFrameSource.h>
#include <roislam/io/TumTrajectory.h>

#include <functional>
#include <memory>
#include <optional>
#include <string>
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
    /** Its parts (backendMs = edgeMs + optimizerMs), and the time MRPT's
     *  engine spent re-estimating every node from its spanning tree after a
     *  new node (outside backendMs; 0 when no node was added), ms. */
    double edgeMs = 0, optimizerMs = 0, spanningTreeMs = 0;
  };

  /** roi-graphslam: our deciders and optimiser, configured by `config`;
   *  `engineIni` (may be empty) configures MRPT's engine itself
   *  ([GeneralConfiguration] class_verbosity, ...). Starts decoding the first
   *  frame at once. Throws std::invalid_argument on invalid options. */
  CSlamPipeline(
      const CSlamContext::TConfig& config, std::unique_ptr<io::CFrameSource> source,
      const std::string& engineIni = "");
  /** roi-graphslam-engine: the deciders and optimiser named `names`
   *  (CRoislamOptionsChecker::createDeciders), their parameters read by
   *  their loadParams() from `iniFile`, which also configures the engine.
   *  `adjust` (may be empty) then changes what they loaded, before the first
   *  frame: the sensor's camera facts (SensorFacts.h). Throws on refused
   *  names and the ini's errors. */
  CSlamPipeline(
      const TSlamDeciders::TNames& names, const std::string& iniFile,
      std::unique_ptr<io::CFrameSource> source,
      const std::function<void(CSlamContext::TConfig&)>& adjust = {});
  /** Waits for a pending decode. */
  ~CSlamPipeline();
  CSlamPipeline(const CSlamPipeline&) = delete;
  CSlamPipeline& operator=(const CSlamPipeline&) = delete;

  /** Processes the next frame; false (and nothing done) at the end of the
   *  sequence. Decoding errors of the source propagate. */
  bool step();

  /** Tells `observer` (not owned; null = none) about the run from now on:
   *  onStart() at once, onFrame() at the end of each step(), onOptimized()
   *  after each optimisation CKeyframeGSO runs (finish() included). */
  void setObserver(CSlamObserver* observer);

  /** Blocks until the next frame is decoded (and its ROI detected): the time
   *  the next step() would wait for it. For benchmarks that time steps of
   *  several pipelines in turn. */
  void waitForPrefetch() const { m_prefetch->waitReady(); }

  /** The final optimisation (call once, after the last step) by
   *  CKeyframeGSO; nullopt with MRPT's optimiser (the graph stays as the
   *  engine left it). */
  std::optional<TOptimizationReport> finish();

  /** Every tracked frame (Lost ones have no pose): a keyframe's optimised
   *  node pose, other frames their reference keyframe's (+) their relative
   *  pose. */
  io::TTrajectory trajectory() const;
  /** A keyframe's optimised pose (its graph node), or the front end's when
   *  it has no node. Throws std::out_of_range on a bad id. */
  mrpt::poses::CPose3D keyframePose(std::size_t id) const;

  const std::vector<TFrameRecord>& records() const { return m_records; }
  /** Optimisations CKeyframeGSO ran so far (loop closures and finish());
   *  nullopt with MRPT's optimiser. */
  std::optional<std::size_t> optimizations() const;
  /** Of those, the ones over the newest keyframes only. */
  std::optional<std::size_t> windowedOptimizations() const;
  const CSlamContext& context() const { return *m_deciders.context; }
  const TGraph& graph() const { return m_engine->getGraph(); }
  const io::CFrameSource& source() const { return *m_source; }
  const TSlamDeciders& deciders() const { return m_deciders; }
  const CRgbdGraphSlamEngine& engine() const { return *m_engine; }
  /** The engine's and each decider's getDescriptiveReport(), one after the
   *  other (report.txt). */
  std::string report() const;

 private:
  /** What the prefetch thread makes of each frame. */
  struct TAhead
  {
    frontend::TPreparedFrame prepared;
    mrpt::obs::CObservation::Ptr observation;
  };

  CSlamPipeline(
      TSlamDeciders deciders, const std::string& engineIni,
      std::unique_ptr<io::CFrameSource> source,
      const std::function<void(CSlamContext::TConfig&)>& adjust);

  std::unique_ptr<io::CFrameSource> m_source;
  TSlamDeciders m_deciders;
  /** Points into m_deciders: declared after it, destroyed before it. */
  std::unique_ptr<CRgbdGraphSlamEngine> m_engine;
  std::vector<TFrameRecord> m_records;
  CSlamObserver* m_observer = nullptr;
  /** The prefetch thread's own front end, for prepare() only (const: it
   *  keeps no per-frame state); the context's one is the tracking thread's. */
  std::unique_ptr<const frontend::CRgbdOdometry> m_preparer;
  /** Decodes, prepares and converts frame i+1 while i is processed (last:
   *  it reads the source and m_preparer, and stops before they go). */
  std::unique_ptr<io::CFramePrefetcher<TAhead>> m_prefetch;
};
}  // namespace roislam::graphslam
