/* The roi-graphslam application: RGB-D graph SLAM over a TUM folder or a
 * rawlog with our deciders (CKeyframeNRD / CKeyframeERD on a
 * CNetworkOfPoses3DInf, driven directly from this loop rather than through
 * CGraphSlamEngine, whose 2.5 version resets optimised poses by Dijkstra),
 * SPA Levenberg-Marquardt on each loop closure and at the end.
 * While frame i is processed, frame i+1 is decoded on a second thread.
 *
 * Writes into the output folder, which is complete or absent
 * (CSlamOutputWriter: staged beside it, renamed into place at the end; a
 * non-empty folder is refused unless `overwrite`):
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
 *  - summary.json    counts, speed, memory, ATE/RPE when ground truth is known,
 *                    display_frame (CGravityFrame::TResult::toJson())
 * trajectory.txt and graph.graph are in the estimate's own frame (the first
 * camera's optical frame, TUM convention: as estimated); map.bt,
 * scene.3Dscene and snapshot.png are gravity-up (z up) in the frame
 * summary.json's display_frame names (CSlamOutputWriter, CGravityFrame).
 * Map and snapshot are built after the timed run (wall_s/fps exclude them;
 * map_s and snapshot_s report them). Called by apps/roi-graphslam and tests.
 */
#pragma once

#include <roislam/evaluation/TEvaluationResult.h>
#include <roislam/graphslam/CSlamContext.h>
#include <roislam/graphslam/CSlamPipeline.h>
#include <roislam/io/TumTrajectory.h>

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace roislam::graphslam
{
class CRoiGraphSlamApp
{
 public:
  struct TArguments
  {
    /** MRPT ini file; empty = defaults. */
    std::string iniFile;
    /** TUM folder or .rawlog. */
    std::string input;
    std::string outputDir;
    /** Command-line overrides of the ini. */
    std::optional<std::string> mode;     //!< [FrontEnd] mode
    std::optional<std::string> feature;  //!< [FeatureExtractor] feature_type
    std::optional<int> maxFeatures;      //!< [FeatureExtractor] max_features
    std::optional<bool> strictRoi;       //!< [FrontEnd] strict_roi
    bool snapshot = true;
    /** Replace an earlier output in outputDir (only our own files). */
    bool overwrite = false;
    /** Camera spec as io::resolveCamera (default auto). */
    std::string camera = "auto";
    /** Process at most this many frames (0 = all). */
    std::size_t maxFrames = 0;
    /** Progress lines (e.g. to stderr); may be empty. */
    std::function<void(const std::string&)> progress;
  };

  /** Headline figures (a subset of summary.json). */
  struct TSummary
  {
    std::size_t frames = 0, keyframes = 0, loopClosures = 0;
    std::size_t trackedFrames = 0, fallbackFrames = 0, lostFrames = 0;
    double wallS = 0, fps = 0, mapS = 0, snapshotS = 0, peakRssMb = 0;
    std::optional<double> ateRmse, rpeTransRmse, rpeRotRmseDeg;
    /** strict_roi lost frames (the dissertation's "no trajectory"). */
    bool failed = false;
    /** What the outputs lack although the run worked (a failed evaluation
     *  against ground truth, a failed snapshot); summary.json "incomplete",
     *  and "partial": true when not empty. The app then exits with
     *  common::kExitPartial unless --allow-partial. */
    std::vector<std::string> incomplete;
    /** "ATE RMSE 0.0042 m, RPE 0.0031 m / 0.21 deg, 90 frames, 31.2 fps". */
    std::string resultLine() const;
  };

  /** Loads the ini (strict keys) and applies the overrides; throws on a bad
   *  file, key or value (message names the file / section / key). */
  explicit CRoiGraphSlamApp(TArguments arguments);

  const CSlamContext::TConfig& config() const { return m_config; }

  /** Runs the whole sequence and writes the outputs. Throws when the input
   *  cannot be read or the output folder is not writable. */
  TSummary run();

  /** "name: description" lines of the registered 3-D node ("node") or edge
   *  ("edge") registration deciders, ours included (CRoislamOptionsChecker). */
  static std::string listRegistrars(const std::string& type);

 private:
  /** The run's error against ground truth, when the sequence has one. */
  struct TEvaluation
  {
    io::TTrajectory groundTruth;
    std::optional<evaluation::TEvaluationResult> result;
    /** ATE of the causal front-end estimate (poses as tracked). */
    std::optional<double> odometryAte;
    /** Why the evaluation failed (empty when it did not). */
    std::string error;
  };

  void progress(const std::string& line) const;
  /** Steps the pipeline to the end (or maxFrames), with progress lines. */
  void runFrames(CSlamPipeline& pipeline, std::size_t total) const;
  TEvaluation evaluate(const CSlamPipeline& pipeline, const io::TTrajectory& estimate) const;
  TSummary summarize(
      const CSlamPipeline& pipeline, const io::TTrajectory& estimate, double wallS,
      const TEvaluation& ev) const;
  nlohmann::json summaryJson(
      const CSlamPipeline& pipeline, const TSummary& s, const TOptimizationReport& finalReport,
      const TEvaluation& ev) const;

  TArguments m_args;
  CSlamContext::TConfig m_config;
};
}  // namespace roislam::graphslam
