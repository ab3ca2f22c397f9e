/* The roi-bench application: plans the dissertation's Tests 1-3 for the given
 * sequences, runs them (parallel, resumable) or prints one shell command per
 * run (--emit-jobs, for GNU parallel over several machines), merges result
 * folders (--merge), and writes results.csv, charts/ (PNG) and report.md into
 * the output folder. apps/roi-bench/roi-bench_main.cpp only parses arguments
 * into TOptions and calls run().
 *
 * App executables are looked up in --bin-dir (as <bin>/<app> or
 * <bin>/<app>/<app>), else next to roi-bench in the build tree
 * (<build>/apps/<app>/<app>) or the install tree (bin/<app>), else on PATH.
 * Config files: --config-dir, else the source tree's config/, else
 * <prefix>/share/roislam/config. Reference numbers: --reference, else the
 * source tree's share/roi-bench/dissertation.json, else
 * <prefix>/share/roislam/roi-bench/dissertation.json.
 *
 * Speed: after the runs, for each Test-2 sequence x extractor, a paired cost
 * measurement (CPairedSlamCost, in this process) of traditional and every
 * Test-2 ROI version whose Test-2 run on it succeeded, `speedPasses` passes,
 * written to speed.json (entry by entry, so an interrupted stage keeps what
 * it measured); report.md's speed table comes from it. Not with --only or
 * --emit-jobs (a part of the runs); --merge combines the folders' speed.json.
 * An entry already in speed.json for the same versions and passes is kept
 * (a failed one is measured again with --retry-failed).
 *
 * Output folder: resumable, so an existing one is used again when it holds
 * only roi-bench's entries (runs/, configs/, results.csv, report.md, charts/,
 * speed.json);
 * anything else is refused. A run's folder is complete when its run.json,
 * written last, exists (a run without it is redone from scratch, the app
 * writing its own output folder complete or absent); results.csv and
 * report.md are renamed into place when complete, charts/ is replaced whole
 * (common::COutputFolder).
 */
#pragma once

#include <roislam/bench/CBenchRunner.h>
#include <roislam/bench/CExperimentPlan.h>
#include <roislam/bench/TRunRecord.h>

#include <ostream>
#include <string>
#include <vector>

namespace roislam::bench
{
class CBenchApp
{
 public:
  struct TOptions
  {
    std::vector<std::string> datasets;  //!< sequence folders or folders of sequences
    std::string outputDir;
    /** Ini with a [Bench] section (CExperimentPlan::TOptions); empty = none. */
    std::string planFile;
    /** Tests to run; empty = the plan file's (else 1,2,3). */
    std::string tests = "1,2,3";
    int jobs = 1;
    bool emitJobs = false;
    std::vector<std::string> mergeDirs;  //!< --merge: result folders to combine
    bool merge = false;
    std::vector<std::string> only;  //!< run ids to execute (empty = all)
    bool noReport = false;
    bool charts = true;
    std::string binDir, configDir, reference;
    double timeoutS = 0;
    bool retryFailed = false;
    std::vector<std::string> variantSpecs;  //!< extra variants, TVariant::parse syntax
    bool noDefaultVariants = false;         //!< drop strict/fallback
    /** cv-odometry methods of the reference rows, "none" = no reference rows
     *  (CExperimentPlan::parseReferenceMethods). */
    std::string referenceMethods = "rgbd,icp,rgbdicp";
    /** Passes of the paired speed measurement after the runs (0 = none:
     *  the speed table from the Test-2 runs alone). */
    int speedPasses = 1;
    std::string selfExe;             //!< path of roi-bench ("" = /proc/self/exe)
    CExperimentPlan::TOptions plan;  //!< tests/variants are set from the fields above
  };

  explicit CBenchApp(const TOptions& options);

  /** Does what the options ask. `out` receives --emit-jobs commands and the
   *  final summary; `err` progress and warnings. Returns the exit code (0,
   *  also when some runs failed: failures are results). Throws on bad input. */
  int run(std::ostream& out, std::ostream& err);

  /** The plan for the options (no file is written). */
  std::vector<TBenchRun> plan() const;
  /** One shell command per run of plan(), each running exactly that run. */
  std::vector<std::string> jobCommands() const;
  /** Executable used for an app name. */
  std::string executableFor(const std::string& app) const;
  std::string configDir() const;
  std::string referenceFile() const;

 private:
  TOptions m_options;
  void writeOutputs(const std::vector<TRunRecord>& records, std::ostream& err) const;
  /** The paired speed stage: speed.json from the Test-2 records. */
  void measurePairedCosts(const std::vector<TRunRecord>& records, std::ostream& err) const;
  /** --merge: the merged folders' speed.json entries into the output's. */
  void mergePairedCosts() const;
};
}  // namespace roislam::bench
