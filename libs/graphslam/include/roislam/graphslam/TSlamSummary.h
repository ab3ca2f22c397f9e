/* Headline figures of one SLAM run (a subset of its summary.json), as
 * CSlamRunner returns them to roi-graphslam and roi-graphslam-engine.
 */
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace roislam::graphslam
{
struct TSlamSummary
{
  std::size_t frames = 0, keyframes = 0, loopClosures = 0;
  std::size_t trackedFrames = 0, fallbackFrames = 0, lostFrames = 0;
  std::size_t graphNodes = 0, graphEdges = 0;
  double wallS = 0, fps = 0, mapS = 0, snapshotS = 0, peakRssMb = 0;
  std::optional<double> ateRmse, rpeTransRmse, rpeRotRmseDeg;
  /** strict_roi lost frames (the dissertation's "no trajectory"). */
  bool failed = false;
  /** The observer stopped the run before the end of the sequence. */
  bool stoppedByUser = false;
  /** What the outputs lack although the run worked (a failed evaluation
   *  against ground truth, a failed snapshot or error plot); summary.json
   *  "incomplete", and "partial": true when not empty. The apps then exit
   *  with common::kExitPartial unless --allow-partial (slamMain). */
  std::vector<std::string> incomplete;
  /** "ATE RMSE 0.0042 m, RPE 0.0031 m / 0.21 deg, 90 frames, 31.2 fps". */
  std::string resultLine() const;
};
}  // namespace roislam::graphslam
