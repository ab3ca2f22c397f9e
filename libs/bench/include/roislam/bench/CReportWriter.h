/* Writes report.md: the dissertation's tables (Test 1 per-sequence landmarks,
 * precision/recall per extractor, with and without hue verification; Test 2
 * mean +- std of ATE / RPE per version x extractor, durations, per-sequence
 * table; Test 3; Test 4, EKF-SLAM vs odometry vs graph SLAM; the reference rows,
 * OpenCV's cv::rgbd odometries beside our best and worst run; speed) from run records,
 * each figure next to the dissertation's. The speed table comes from the
 * paired measurement (speed.json, CPairedSlamCost) when there is one, else
 * from the Test-2 runs' own summaries (written by CSpeedTableWriter, private
 * to libs/bench, as are the other sections' writers). Failed runs appear as
 * failures, never dropped. Called by CBenchApp after the runs.
 */
#pragma once

#include <roislam/bench/CDissertationReference.h>
#include <roislam/bench/TPairedCost.h>
#include <roislam/bench/TRunRecord.h>

#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace roislam::bench
{
/** Mean and sample standard deviation (n - 1; 0 when n == 1) of values. */
struct TMeanStd
{
  double mean = 0, std = 0;
  std::size_t n = 0;
};
std::optional<TMeanStd> meanStd(const std::vector<double>& values);

class CReportWriter
{
 public:
  struct TOptions
  {
    int jobs = 1;                     //!< parallel runs used (timings are per run, under that load)
    std::vector<std::string> charts;  //!< PNG paths relative to the report, embedded
    /** roi-bench's speed.json (paired cost per sequence x extractor); "" =
     *  none: the speed table from the Test-2 runs' single measurements. */
    std::string pairedCostFile;
  };

  /** Reads options.pairedCostFile when set: throws std::runtime_error
   *  "<file>: ..." (one line) when it is missing or malformed. */
  CReportWriter(const TOptions& options, const CDissertationReference& reference);

  /** The markdown text for these records (in plan order). */
  std::string render(const std::vector<TRunRecord>& records) const;
  /** render() written atomically to `file`. */
  void write(const std::vector<TRunRecord>& records, const std::string& file) const;

  /** Report label of a version key ("roi_big/strict" -> "big ROI, strict ROI ..."). */
  static std::string versionLabel(const TRunRecord& rec);

 private:
  using TRecordList = std::vector<const TRunRecord*>;

  // The tests' sections are written by CTest1TableWriter,
  // CTrajectoryTableWriter (Tests 2-4), report::renderReference and
  // CSpeedTableWriter (libs/bench/src, private); these are the rest.
  void renderIntroduction(std::ostream& md, const std::vector<TRunRecord>& records) const;
  void renderSequences(std::ostream& md, const TRecordList& all) const;
  void renderFailures(std::ostream& md, const std::vector<TRunRecord>& records) const;

  TOptions m_options;
  CDissertationReference m_ref;
  std::vector<TPairedCost> m_paired;  //!< from options.pairedCostFile, for the speed section
};
}  // namespace roislam::bench
