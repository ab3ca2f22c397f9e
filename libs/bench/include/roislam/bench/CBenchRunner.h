/* Executes benchmark runs as subprocesses, up to `jobs` at a time, each in
 * its own folder: <runDir>/command.sh (the exact command), stdout.log,
 * stderr.log, output/ (the app's --output-dir) and finally run.json (the
 * completion marker, written atomically). A run whose run.json exists is
 * skipped (resume); a failed one too unless retry_failed. Called by CBenchApp.
 *
 * Options (set in code or from roi-bench's command line):
 *   jobs               int >= 1   1   runs in parallel
 *   timeout_s          double     0   s per run, 0 = none; exceeded -> killed, failed
 *   retry_failed       bool       false  rerun runs whose run.json says failed
 *   stderr_tail_lines  int        15  lines of stderr kept in run.json
 */
#pragma once

#include <roislam/bench/TBenchRun.h>
#include <roislam/bench/TRunRecord.h>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace roislam::bench
{
class CBenchRunner
{
 public:
  struct TOptions
  {
    int jobs = 1;
    double timeout_s = 0;
    bool retry_failed = false;
    int stderr_tail_lines = 15;
  };

  struct TProgress
  {
    std::size_t total = 0;    //!< runs in the batch
    std::size_t done = 0;     //!< finished, including skipped
    std::size_t skipped = 0;  //!< already complete before this call
    std::size_t failed = 0;
    double elapsedS = 0;
    std::optional<double> etaS;  //!< nullopt until a run has been timed
    std::string lastId;          //!< run that just finished
  };
  using TProgressCallback = std::function<void(const TProgress&)>;

  CBenchRunner();
  /** Throws std::invalid_argument when jobs < 1. */
  explicit CBenchRunner(const TOptions& options);

  /** Runs (or skips) every run; returns one record per run, in input order.
   *  The callback is called from one thread at a time. */
  std::vector<TRunRecord> run(
      const std::vector<TBenchRun>& runs, const TProgressCallback& progress = {}) const;

  /** Executes one run now (clears its output/ and logs first). */
  TRunRecord runOne(const TBenchRun& run) const;

  /** The record of a completed run folder, nullopt when run.json is absent.
   *  Throws std::runtime_error naming the file when it is corrupt. */
  static std::optional<TRunRecord> loadCompleted(const std::string& runDir);

 private:
  TOptions m_options;
};
}  // namespace roislam::bench
