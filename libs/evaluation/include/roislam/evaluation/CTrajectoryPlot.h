/* PNG figure of a ground-truth trajectory and one or more named estimates
 * (already aligned to the ground truth, e.g. TEvaluationResult::aligned):
 * left a top view, right the height over time. Used by roi-eval --plot and by
 * the experiment report ("ground truth vs the three SLAM versions").
 *
 * Runs Debian's gnuplot (package gnuplot-nox) as a subprocess on a generated
 * script and data files in a temporary folder; the pngcairo terminal is used
 * when gnuplot has it, else png. Lines break where a trajectory has a gap of
 * more than gap_break seconds, so missing stretches stay visible.
 *
 * The "up" axis (plotted over time; the other two form the top view) is
 * chosen by up_axis; "auto" (autoUpAxis()) assumes camera poses in the TUM
 * optical convention (x right, y down, z forward), whose x axis stays nearly
 * horizontal for hand-held and robot motion: up is the world axis least
 * visited by the camera x axis (ties: the one most aligned with the camera y
 * axis). This gives z for TUM ground truth and our simulator (z up), also
 * for rotation-only sequences where position ranges say nothing.
 */
#pragma once

#include <roislam/io/TumTrajectory.h>

#include <string>
#include <utility>
#include <vector>

namespace roislam::evaluation
{
class CTrajectoryPlot
{
 public:
  struct TOptions
  {
    std::string title;                //!< figure title (e.g. the sequence name)
    int width = 1400;                 //!< pixels
    int height = 600;                 //!< pixels
    std::string up_axis = "auto";     //!< auto | x | y | z
    double gap_break = 1.0;           //!< s; larger stamp gaps are not joined by a line
    std::string gnuplot = "gnuplot";  //!< executable (looked up in PATH)
  };
  using TNamedTrajectory = std::pair<std::string, io::TTrajectory>;

  CTrajectoryPlot();
  explicit CTrajectoryPlot(const TOptions& options);

  /** Writes `pngFile` (through a temporary name, renamed when complete).
   *  `groundTruth` may be empty (then "auto" uses the first estimate).
   *  Throws std::runtime_error when gnuplot is missing or fails, when there is
   *  nothing to plot, or when the file cannot be written. */
  void plot(
      const std::string& pngFile, const io::TTrajectory& groundTruth,
      const std::vector<TNamedTrajectory>& estimates) const;

  /** The axis up_axis = "auto" picks for these camera poses: 0 = x, 1 = y,
   *  2 = z (z for an empty trajectory). */
  static int autoUpAxis(const io::TTrajectory& cameraPoses);

  const TOptions& options() const { return m_options; }

 private:
  TOptions m_options;
};
}  // namespace roislam::evaluation
