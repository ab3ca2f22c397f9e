/* Writes the files of one finished SLAM run into its output folder (see
 * CRoiGraphSlamApp.h for the list and their content). One writer per output
 * folder; the run's data comes in through a TRun view, so any driver of our
 * deciders (roi-graphslam's own loop, MRPT's engine) writes the same files.
 * Called by CRoiGraphSlamApp.
 *
 * The folder is complete or absent (common::COutputFolder): the files go to a
 * staging folder beside it, and writeSummary(), the last call, writes
 * summary.json and renames the folder into place. A writer destroyed before
 * that (an exception while writing the map, say) leaves the output folder
 * absent or as it was. An existing non-empty folder is refused unless
 * `overwrite`, which replaces an earlier output of ours (files()).
 *
 * Frames: trajectory.txt and graph.graph keep the estimate's own world (the
 * first camera's optical frame, TUM convention); the pictures (map.bt,
 * scene.3Dscene, snapshot.png) are drawn gravity-up in the frame
 * CGravityFrame chooses (ground truth, accelerometer or first camera),
 * recorded in summary.json's "display_frame" (TPictures::addToSummary).
 */
#pragma once

#include <roislam/common/COutputFolder.h>
#include <roislam/evaluation/TEvaluationResult.h>
#include <roislam/graphslam/CGravityFrame.h>
#include <roislam/graphslam/CSlamPipeline.h>
#include <roislam/io/TumTrajectory.h>
#include <roislam/viz/TSceneContent.h>

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace roislam::graphslam
{
class CSlamOutputWriter
{
 public:
  /** What a finished run hands to the writer (references: the run outlives
   *  the writer's calls). */
  struct TRun
  {
    const std::vector<CSlamPipeline::TFrameRecord>& records;
    const CSlamContext& context;
    const TGraph& graph;
    /** Optimised world pose of a keyframe. */
    std::function<mrpt::poses::CPose3D(std::size_t)> keyframePose;
  };

  /** What the pictures compare the run with and how they are labelled. */
  struct TReference
  {
    std::string sequence;             //!< name shown in the legend and plot titles
    const io::TTrajectory& estimate;  //!< the run's trajectory, as estimated
    /** Ground truth (TUM), empty when unknown. */
    const io::TTrajectory& groundTruth;
    /** `estimate` against `groundTruth`; null when unknown or failed. */
    const evaluation::TEvaluationResult* evaluation = nullptr;
    std::optional<std::string> accelerometerFile;  //!< TUM accelerometer.txt, if any
  };

  /** What writePictures() did. */
  struct TPictures
  {
    CGravityFrame::TResult frame;  //!< the frame of map, scene and snapshot
    double mapS = 0;               //!< map.bt
    double snapshotS = 0;          //!< scene, snapshot and plots
    std::string snapshotError;     //!< why snapshot.png is missing (empty: written or not asked)
    std::string plotError;         //!< why ate.png / errors.png are missing despite an evaluation

    /** One line each: a missing snapshot or plot, an accelerometer log that
     *  could not level the pictures. */
    std::vector<std::string> warnings() const;
    /** Adds "display_frame" (CGravityFrame::TResult::toJson()) and, when
     *  set, "snapshot_error" and "plot_error" to a summary. */
    void addToSummary(nlohmann::json& summary) const;
  };

  /** Prepares the staging folder; throws "output dir <dir>: ..." when `dir`
   *  cannot be written, is not a folder or is not empty (unless overwrite
   *  and it holds only our files). Construct it before the run, so a bad
   *  folder fails before the work. */
  explicit CSlamOutputWriter(const std::string& outputDir, bool overwrite = false);

  /** Where the files go now: the staging folder until writeSummary(),
   *  then the output folder. */
  std::string folder() const { return m_folder.path(); }

  /** The names this writer may put into an output folder. */
  static const std::vector<std::string>& files();

  void writeTrajectory(const io::TTrajectory& estimate, const std::string& header) const;
  void writeGraph(const TGraph& graph) const;
  /** frames.csv: one row per frame (CRoiGraphSlamApp.h). */
  void writeFramesCsv(const std::vector<CSlamPipeline::TFrameRecord>& records) const;
  /** report.txt: MRPT's engine report and the deciders' (CSlamRunner.h). */
  void writeReport(const std::string& text) const;
  /** The pictures of a run, in the gravity-up frame (CGravityFrame::choose):
   *  map.bt, scene.3Dscene, snapshot.png when `snapshot`, and, when the
   *  evaluation is known, ate.png (CTrajectoryPlot: top view and height over
   *  time) and errors.png (CErrorPlot: ATE and RPE over time). Throws on map
   *  or scene errors; a missing snapshot or plot is reported in the result. */
  TPictures writePictures(const TRun& run, const TReference& reference, bool snapshot) const;

  /** map.bt (OctoMap, 5 cm) from the keyframes' clouds, in the frame
   *  `toDisplay` (+) world; returns a decimated coloured cloud of the same
   *  points for the scene. */
  viz::TSceneContent writeMap(const TRun& run, const mrpt::poses::CPose3D& toDisplay) const;
  /** scene.3Dscene, and snapshot.png when `snapshot`; returns the snapshot's
   *  error (empty on success or when not asked). Throws on scene errors. */
  std::string writeScene(const viz::TSceneContent& content, bool snapshot) const;
  /** ate.png and errors.png of an evaluation; returns the first error (empty on success). */
  std::string writePlots(const TReference& reference) const;
  /** Writes summary.json and moves the folder into place: the last call. */
  void writeSummary(const nlohmann::json& summary);

  /** Writes text through `file`.tmp renamed on success; throws "<file>: ...". */
  static void writeTextFile(const std::string& file, const std::string& text);

 private:
  common::COutputFolder m_folder;
  std::string m_dir;  //!< the staging folder, with a trailing '/'
};
}  // namespace roislam::graphslam
