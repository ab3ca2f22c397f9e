/* Collects run records from output folders (<dir>/runs/<id>/run.json), merges
 * result folders produced on several machines, and writes results.csv: one
 * row per run with every figure and the exact command. Used by CBenchApp.
 */
#pragma once

#include <roislam/bench/TBenchRun.h>
#include <roislam/bench/TRunRecord.h>

#include <string>
#include <vector>

namespace roislam::bench
{
class CResultsCollector
{
 public:
  /** Every completed run under <outputDir>/runs, sorted by id; run folders
   *  are re-rooted at their current location. Throws on a corrupt run.json. */
  static std::vector<TRunRecord> loadFolder(const std::string& outputDir);

  /** Copies the run folders of each source output folder into
   *  <dest>/runs: a run missing in dest is copied; a failed one in dest is
   *  replaced by a successful one. Returns the records now in dest. */
  static std::vector<TRunRecord> merge(
      const std::vector<std::string>& sources, const std::string& dest);

  /** Records in plan order for the planned runs (missing ones left out),
   *  then any other completed record. */
  static std::vector<TRunRecord> orderByPlan(
      const std::vector<TRunRecord>& records, const std::vector<TBenchRun>& plan);

  /** results.csv text: fixed columns, then every summary field seen. */
  static std::string toCsv(const std::vector<TRunRecord>& records);
  static void writeCsv(const std::vector<TRunRecord>& records, const std::string& file);
};
}  // namespace roislam::bench
