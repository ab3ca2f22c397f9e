/* The roi-landmarks application (the dissertation's Test 1, the pipeline
 * alone): reads an RGB-D sequence (TUM folder or rawlog), runs the ROI
 * landmark pipeline on every frame and writes into the output folder:
 *  - frames.csv     one record per frame: frame, timestamp, status ("landmark
 *                   k" / "no new ROI" / "NaN"), landmark, new, matches,
 *                   false_matches, seconds, features, roi_features,
 *                   depth_valid, depth_mean_m, depth_median_m, roi_x/y/w/h,
 *                   recall_inliers, candidates, roi_pos_x/y/z (optical frame,
 *                   m), lm_x/y/w/h and lm_pos_x/y/z (the landmark located in
 *                   this frame), rigid_pairs, rigid_rms_m, cpu_seconds,
 *                   s_roi/s_features/s_confirm/s_query (stage times), score and
 *                   alt_score (TP/FP/FN/TN with ground truth, primary and
 *                   alternative recall position)
 *  - landmarks/     each new landmark's ROI patch, named by frame (000123.png)
 *  - landmarks.db   the database (gzip MRPT archive, CLandmarkDatabase)
 *  - summary.json   counts, ground-truth scores (null without ground truth;
 *                   "recall_position" and "alternative_scoring": see
 *                   TSummary), matches per frame, duration and
 *                   speed (duration_s/fps: pipeline wall time without I/O;
 *                   wall_s/fps_wall: whole run)
 *  - optionally an annotated rawlog: per frame the CObservation3DRangeScan
 *    followed by its CObservationBearingRange (observation-only format).
 *  - with kfSlam (--kf-slam): kf-slam.rawlog (per frame the front end's
 *    odometry as a CActionRobotMovement3D and a CSensoryFrame with the
 *    frame's CObservationBearingRange), kf-slam/trajectory.txt (MRPT's
 *    EKF-SLAM, TUM), kf-slam/odometry.txt, kf-slam/landmarks.txt,
 *    kf-slam.landmarks_gt.txt with ground truth, and summary.json's
 *    "kf_slam" object (kfslam::CKfSlamSession; [KfSlam] options).
 * The output folder is complete or absent (common::COutputFolder: written
 * into a staging folder beside it, renamed into place at the end); a
 * non-empty folder is refused unless `overwrite` (only our files, with the
 * annotated rawlog when it is inside). An annotated rawlog outside the folder
 * is written under a temporary name renamed when complete.
 * Called by apps/roi-landmarks (thin main) and the tests.
 */
#pragma once

#include <roislam/common/COutputFolder.h>
#include <roislam/io/CFrameSource.h>
#include <roislam/kfslam/CKfSlamSession.h>
#include <roislam/landmarks/TPipelineOptions.h>

#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace roislam::landmarks
{
class CRoiLandmarksApp
{
 public:
  struct TArguments
  {
    /** ini file; empty = defaults. */
    std::string iniFile;
    /** TUM folder or .rawlog. */
    std::string input;
    std::string outputDir;
    /** Overrides of the ini (command-line flags). */
    std::optional<std::string> feature;
    std::optional<int> maxFeatures;
    std::optional<std::string> roiPreset;
    std::optional<std::string> outputRawlog;
    /** Replace an earlier output in outputDir (only our own files). */
    bool overwrite = false;
    /** Camera spec as io::resolveCamera (default auto). */
    std::string camera = "auto";
    /** Process at most this many frames (0 = all). */
    std::size_t maxFrames = 0;
    /** Also run MRPT's EKF-SLAM on the landmarks ([KfSlam] options). */
    bool kfSlam = false;
    /** Progress lines (e.g. to stderr); may be empty. */
    std::function<void(const std::string&)> progress;
  };

  /** Headline figures, as written to summary.json. */
  struct TSummary
  {
    std::size_t frames = 0;
    std::size_t framesWithRoi = 0;
    /** [RoiDetector] verify_hue: frames whose grey ROI the hue detector
     *  did not confirm (they count as frames without a ROI). */
    std::size_t framesRejectedByHue = 0;
    std::size_t confirmedRois = 0;
    std::size_t landmarks = 0;
    std::size_t recalls = 0;
    std::optional<int> truePositives, falsePositives, falseNegatives, unscored;
    /** Ground-truth scores (CLandmarkScorer) with the recall position chosen
     *  by [LandmarkScoring] recall_position (default landmark_point: the
     *  recalled landmark's stored point carried into the frame by the 3-D
     *  alignment of the match, TFrameResult::landmarkPosition; roi_median:
     *  the median 3-D point of the ROI box's features). */
    std::optional<double> precision, recall;
    std::string recallPosition;
    /** The same counts with the other recall position. */
    std::string altRecallPosition;
    std::optional<int> altFalsePositives, altFalseNegatives;
    std::optional<double> altPrecision, altRecall;
    double matchesPerFrame = 0;
    double falseMatchesPerFrame = 0;
    /** Pipeline time (sum of per-frame processing, no I/O) and its fps. */
    double durationS = 0;
    double fps = 0;
    /** CPU time of the pipeline's calling thread (OpenCV worker threads,
     *  used by SIFT, not included). */
    double cpuS = 0;
    /** Wall time of the whole run including reading and writing. */
    double wallS = 0;
    /** With kfSlam: summary.json's "kf_slam" object, else null. */
    nlohmann::json kfSlam;
  };

  explicit CRoiLandmarksApp(TArguments arguments);

  /** Loads the configuration and applies the overrides; throws on errors
   *  (message names the file / section / key). */
  const TPipelineOptions& options() const { return m_options; }

  /** Runs the whole sequence and writes the outputs. */
  TSummary run();

  /** The names run() may put into the output folder (besides an annotated
   *  rawlog inside it): what --overwrite may replace. */
  static const std::vector<std::string>& outputFiles();

 private:
  common::COutputFolder::TOptions outputFolderOptions(
      const std::optional<std::filesystem::path>& rawlogInFolder) const;
  void progress(const std::string& line) const;
  /** EKF-SLAM's setup for `source`, writing into `outputDir` (the staging
   *  folder) and reporting paths in `finalOutputDir` (the target). */
  kfslam::CKfSlamSession::TSetup kfSlamSetup(
      const io::CFrameSource& source, const std::string& outputDir,
      const std::string& finalOutputDir) const;

  TArguments m_args;
  TPipelineOptions m_options;
};
}  // namespace roislam::landmarks
