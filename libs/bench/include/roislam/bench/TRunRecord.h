/* The outcome of one benchmark run: the run, its status, timing measured by
 * the runner, the tail of its stderr and the app's summary.json. Written as
 * <runDir>/run.json by CBenchRunner (its presence marks a completed run),
 * read back by CResultsCollector, CReportWriter and CChartWriter.
 */
#pragma once

#include <roislam/bench/TBenchRun.h>

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace roislam::bench
{
struct TRunRecord
{
  TBenchRun run;
  bool ok = false;            //!< exit 0, summary.json present, no "failed": true
  std::string failureReason;  //!< one line when !ok
  int exitCode = -1;
  int signal = 0;
  bool timedOut = false;
  double wallS = 0;     //!< s, measured by the runner around the whole process
  double cpuS = 0;      //!< s, user + system
  double maxRssMb = 0;  //!< MiB, peak RSS from wait4
  std::string startedUtc;
  std::string host;
  std::string stderrTail;
  nlohmann::json summary;  //!< the app's summary.json, null when absent

  /** A summary field, or nullptr: a key as it is, else "a.b..." for field
   *  b of object a, any depth deep. */
  const nlohmann::json* field(const std::string& key) const;
  /** A numeric summary field (field()), nullopt when missing, null or not a
   *  number. */
  std::optional<double> number(const std::string& key) const;

  nlohmann::json toJson() const;
  /** Throws std::runtime_error on a malformed record. */
  static TRunRecord fromJson(const nlohmann::json& j);
};
}  // namespace roislam::bench
