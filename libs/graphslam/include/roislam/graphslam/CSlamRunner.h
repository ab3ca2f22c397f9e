/* Runs one SLAM pipeline (CSlamPipeline: MRPT's engine with the chosen
 * deciders) over its sequence and writes the run's outputs into the output
 * folder, which is complete or absent: the files are staged beside it and
 * the folder is renamed into place after summary.json (CSlamOutputWriter,
 * common::COutputFolder); a non-empty folder is refused unless
 * TSettings::overwrite, which replaces an earlier output of ours whole. What roi-graphslam
 * (CRoiGraphSlamApp) and roi-graphslam-engine (CRoiGraphSlamEngineApp) both do once their
 * configuration is known, so they write the same files the same way:
 *  - trajectory.txt  TUM format, colour stamps; every tracked frame: its
 *                    keyframe's optimised pose (+) its pose relative to it
 *  - graph.graph     the optimised keyframe graph (MRPT text format, graph-slam)
 *  - map.bt          OctoMap (5 cm) of the keyframes' decimated clouds
 *  - scene.3Dscene   map cloud + trajectory with keyframes (+ ground truth), SceneViewer3D
 *  - snapshot.png    offscreen picture of that scene: 3-D and top views, legend
 *                    (unless disabled)
 *  - ate.png         with ground truth: top view and height over time (CTrajectoryPlot)
 *  - errors.png      with ground truth: ATE and RPE over time (CErrorPlot)
 *  - frames.csv      per frame: tracking method, counts, ROI, per-stage ms
 *  - report.txt      MRPT's engine report (edge counts, timings, log) and each
 *                    decider's and the optimiser's getDescriptiveReport()
 *                    (description, parameters in use, counters)
 *  - summary.json    counts, speed, memory, ATE/RPE when ground truth is known,
 *                    edge_chi2 (the graph edges' chi² against the ground
 *                    truth's relative poses, per direction and per edge
 *                    kind, and with the ground truth's measured noise
 *                    added, evaluation::edgeChi2),
 *                    display_frame (CGravityFrame::TResult::toJson()), the
 *                    deciders' names ("engine"); "partial" and "incomplete"
 *                    (TSlamSummary::incomplete)
 * trajectory.txt and graph.graph are in the estimate's own frame (the first
 * camera's optical frame, TUM convention: as estimated); map.bt,
 * scene.3Dscene and snapshot.png are gravity-up (z up) in the frame
 * summary.json's display_frame names (CSlamOutputWriter, CGravityFrame).
 * Map and snapshot are built after the timed run (wall_s/fps exclude them;
 * map_s and snapshot_s report them).
 */
#pragma once

#include <roislam/evaluation/EdgeChi2.h>
#include <roislam/evaluation/TEvaluationResult.h>
#include <roislam/graphslam/CSlamObserver.h>
#include <roislam/graphslam/CSlamOutputWriter.h>
#include <roislam/graphslam/CSlamPipeline.h>
#include <roislam/graphslam/TSlamSummary.h>
#include <roislam/io/CFrameSource.h>
#include <roislam/io/TumTrajectory.h>

#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace roislam::graphslam
{
class CSlamRunner
{
 public:
  struct TSettings
  {
    /** Prefix of progress lines and the trajectory's header. */
    std::string app;
    /** As given by the user (summary.json "input"). */
    std::string input;
    std::string outputDir;
    /** Replace an earlier output of ours in outputDir (CSlamOutputWriter). */
    bool overwrite = false;
    /** TUM-format ground truth; none: no ATE / RPE. */
    std::optional<std::string> groundTruthFile;
    bool snapshot = true;
    /** Process at most this many frames (0 = all). */
    std::size_t maxFrames = 0;
    /** Progress lines (e.g. to stderr); may be empty. */
    std::function<void(const std::string&)> progress;
    /** Called once the pipeline is built (its parameters loaded); may be empty. */
    std::function<void(const CSlamPipeline&)> started;
    /** Watches the run (the live view); not owned, may be null. Its
     *  stopRequested() ends the run early, the outputs still written. */
    CSlamObserver* observer = nullptr;
    /** Where the front end's rolling-shutter readout came from
     *  (summary.json sensor.rolling_shutter_from). */
    std::string readoutFrom = "ini";
  };
  using TMakePipeline =
      std::function<std::unique_ptr<CSlamPipeline>(std::unique_ptr<io::CFrameSource>)>;

  explicit CSlamRunner(TSettings settings);

  /** Checks the output folder (and prepares its staging folder), builds the pipeline over `source`,
   * runs the whole sequence (or maxFrames), and writes the outputs. Throws when the output folder
   * is not writable, the pipeline cannot be built or a frame cannot be read. */
  TSlamSummary run(std::unique_ptr<io::CFrameSource> source, const TMakePipeline& make) const;

 private:
  /** The run's error against ground truth, when it is known. */
  struct TEvaluation
  {
    io::TTrajectory groundTruth;
    std::optional<evaluation::TEvaluationResult> result;
    /** ATE of the causal front-end estimate (poses as tracked). */
    std::optional<double> odometryAte;
    /** The graph edges' chi² against the ground truth's relative poses. */
    std::optional<evaluation::TEdgeChi2> edgeChi2;
    /** Why the evaluation failed (empty when it did not). */
    std::string error;
  };

  void progress(const std::string& line) const;
  /** Steps the pipeline to the end (or maxFrames, or until the observer
   *  asks to stop: returns true then), with progress lines. */
  bool runFrames(CSlamPipeline& pipeline, std::size_t total) const;
  TEvaluation evaluate(const CSlamPipeline& pipeline, const io::TTrajectory& estimate) const;
  /** The graph edges' chi² against the ground truth, by kind: "loop"
   *  (accepted closures), "odometry" (consecutive keyframes), "keyframe"
   *  (the other edges to recent keyframes). */
  static std::optional<evaluation::TEdgeChi2> edgeChi2(
      const CSlamPipeline& pipeline, const io::TTrajectory& groundTruth);
  TSlamSummary summarize(
      const CSlamPipeline& pipeline, const io::TTrajectory& estimate, double wallS,
      const TEvaluation& ev) const;
  nlohmann::json summaryJson(
      const CSlamPipeline& pipeline, const TSlamSummary& s,
      const std::optional<TOptimizationReport>& finalReport, const TEvaluation& ev) const;
  /** The files of the run, after the timed part. */
  void writeOutputs(
      CSlamOutputWriter& writer, const CSlamPipeline& pipeline, const io::TTrajectory& estimate,
      const std::optional<TOptimizationReport>& finalReport, const TEvaluation& ev,
      TSlamSummary& s) const;

  TSettings m_settings;
};
}  // namespace roislam::graphslam
