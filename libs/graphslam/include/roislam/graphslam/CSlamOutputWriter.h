/* Writes the files of one finished SLAM run into its output folder, each
 * under a temporary name renamed when complete (see CRoiGraphSlamApp.h for
 * the list and their content). One writer per output folder; the run's data
 * comes in through a TRun view, so any driver of our deciders (roi-graphslam's
 * own loop, MRPT's engine) writes the same files. Called by CRoiGraphSlamApp.
 */
#pragma once

#include <roislam/evaluation/TEvaluationResult.h>
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

  /** The folder must exist and be writable (checkWritableDir). */
  explicit CSlamOutputWriter(std::string outputDir);

  /** Creates `dir` if needed and checks that a file can be written there;
   *  throws "output dir <dir>: ..." otherwise. */
  static void checkWritableDir(const std::string& dir);

  void writeTrajectory(const io::TTrajectory& estimate, const std::string& header) const;
  void writeGraph(const TGraph& graph) const;
  /** frames.csv: one row per frame (CRoiGraphSlamApp.h). */
  void writeFramesCsv(const std::vector<CSlamPipeline::TFrameRecord>& records) const;
  /** map.bt (OctoMap, 5 cm) from the keyframes' clouds in the world frame;
   *  returns a decimated coloured cloud of the same points for the scene. */
  viz::TSceneContent writeMap(const TRun& run) const;
  /** scene.3Dscene, and snapshot.png when `snapshot`; returns the snapshot's
   *  error (empty on success or when not asked). Throws on scene errors. */
  std::string writeScene(const viz::TSceneContent& content, bool snapshot) const;
  void writeSummary(const nlohmann::json& summary) const;

  /** Writes text through `file`.tmp renamed on success; throws "<file>: ...". */
  static void writeTextFile(const std::string& file, const std::string& text);

 private:
  std::string m_dir;  //!< with a trailing '/'
};
}  // namespace roislam::graphslam
