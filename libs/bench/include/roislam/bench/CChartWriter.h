/* Draws roi-bench's PNG charts with gnuplot (a subprocess): Test 1 bar charts
 * per sequence (landmarks, false positives, false negatives), Tests 2-3 bar
 * charts per version x extractor with std error bars (ATE, RPE translation,
 * RPE rotation, duration), and a top-view trajectory plot per sequence and
 * extractor (ground truth vs each version, estimates aligned as for the ATE),
 * and Test 4's ATE bars (EKF-SLAM, odometry alone, graph SLAM).
 * Each chart's data (.dat) and script (.gp) stay next to its PNG. Called by
 * CBenchApp; a chart whose data are all missing is not drawn.
 *
 * Options (code only): gnuplot (executable, default "gnuplot"), width/height (px).
 */
#pragma once

#include <roislam/bench/TRunRecord.h>
#include <roislam/io/TumTrajectory.h>

#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace roislam::bench
{
class CChartWriter
{
 public:
  struct TOptions
  {
    std::string gnuplot = "gnuplot";
    int width = 1000, height = 600;
  };

  CChartWriter();
  explicit CChartWriter(const TOptions& options);

  /** True when the gnuplot executable can be found. */
  bool available() const;

  /** Writes every chart into `dir` (created); returns the PNG file names
   *  (relative to dir). Throws std::runtime_error naming the script when
   *  gnuplot fails. */
  std::vector<std::string> write(const std::vector<TRunRecord>& records, const std::string& dir);

  /** Problems that did not stop the charts (e.g. a trajectory that could not be aligned). */
  const std::vector<std::string>& warnings() const { return m_warnings; }

 private:
  TOptions m_options;
  std::vector<std::string> m_warnings;
  void plot(const std::string& dir, const std::string& name, const std::string& script);

  /** Test 1: clustered bars per sequence, one bar per extractor. */
  std::vector<std::string> writeTest1(
      const std::vector<TRunRecord>& records, const std::string& dir);
  /** Tests 2-3: one chart per metric, mean +- std per version and extractor. */
  std::vector<std::string> writeVersionCharts(
      const std::vector<TRunRecord>& records, const std::string& dir, int test);
  /** metric = {summary key, axis label, chart name suffix}; nullopt when no value. */
  std::optional<std::string> writeVersionChart(
      const std::vector<TRunRecord>& records, const std::string& dir, int test,
      const std::vector<std::pair<std::string, std::string>>& versions,
      const std::vector<std::string>& feats, const std::array<std::string, 3>& metric);
  /** Top views of Test 2 per sequence and extractor. */
  std::vector<std::string> writeTrajectories(
      const std::vector<TRunRecord>& records, const std::string& dir);
  std::optional<std::string> writeTrajectory(
      const std::string& dir, const std::string& sequence, const std::string& feature,
      const std::vector<const TRunRecord*>& runs);
  /** Test 4: ATE of EKF-SLAM, odometry alone and graph SLAM per sequence
   *  and extractor; nullopt without Test 4 runs. */
  std::optional<std::string> writeTest4(
      const std::vector<TRunRecord>& records, const std::string& dir);
  /** The gnuplot plot clause of run number idx (1-based) of a top view. */
  std::string trajectoryPlot(
      const std::string& dir, const std::string& name, int idx, const TRunRecord& run,
      const io::TTrajectory& gt, int ax, int ay);
};
}  // namespace roislam::bench
