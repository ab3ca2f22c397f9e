// roi-bench: runs the dissertation's Tests 1-3 on the given sequences and
// writes results.csv, charts and report.md (logic in roislam::bench::CBenchApp).
#include <roislam/bench/CBenchApp.h>
#include <roislam/common/ProcessTuning.h>

#include <CLI/CLI.hpp>
#include <iostream>

namespace
{
void addOptions(CLI::App& cli, roislam::bench::CBenchApp::TOptions& o, bool& noCharts)
{
  cli.add_option("--datasets", o.datasets, "Sequence folders, or folders of sequences")
      ->expected(1, -1);
  cli.add_option("--output-dir", o.outputDir, "Results folder (runs/, results.csv, report.md)")
      ->required();
  cli.add_option("--tests", o.tests, "Tests to run, e.g. 1,2,3 (4: EKF-SLAM on ROI landmarks)")
      ->capture_default_str();
  cli.add_option("--plan", o.planFile, "Ini with a [Bench] section (features, modes, caps...)");
  cli.add_option("--jobs", o.jobs, "Runs in parallel")->capture_default_str();
  cli.add_flag("--emit-jobs", o.emitJobs, "Print one shell command per run and exit");
  cli.add_option("--merge", o.mergeDirs, "Combine these result folders into --output-dir")
      ->expected(0, -1);
  cli.add_option("--only", o.only, "Execute only these run ids")->expected(1, -1);
  cli.add_flag("--no-report", o.noReport, "Run only; write no results.csv/report");
  cli.add_option("--bin-dir", o.binDir, "Folder with roi-landmarks / roi-graphslam / cv-odometry");
  cli.add_option("--config-dir", o.configDir, "Folder with the apps' .ini files");
  cli.add_option("--reference", o.reference, "The dissertation's numbers (dissertation.json)");
  cli.add_option(
         "--speed-passes", o.speedPasses,
         "Passes of the paired speed measurement after the runs (Test-2 versions stepped in "
         "turn frame by frame; 0 = off: speed table from the single runs)")
      ->capture_default_str();
  cli.add_option("--timeout", o.timeoutS, "Seconds per run before it is killed (0 = none)");
  cli.add_flag("--retry-failed", o.retryFailed, "Rerun runs recorded as failed");
  cli.add_option("--variant", o.variantSpecs, "Extra variant name:Section.key=value[,...]");
  cli.add_flag(
      "--no-default-variants", o.noDefaultVariants,
      "Drop the default variants (strict/fallback/roicap/region, Test 1's hue)");
  cli.add_option(
         "--reference-methods", o.referenceMethods,
         "Reference rows: cv-odometry methods (rgbd,icp,rgbdicp) per sequence, or none")
      ->capture_default_str();
  cli.footer(
      "Several machines: roi-bench ... --emit-jobs | parallel --sshlogin m1,m2 (shared output\n"
      "folder), or give each machine its own --output-dir and combine them with\n"
      "roi-bench --output-dir ALL --merge DIR1 DIR2 [--datasets ...].");
  cli.add_flag("--no-charts", noCharts, "Do not draw PNG charts");
}
}  // namespace

int main(int argc, char** argv)
{
  roislam::bench::CBenchApp::TOptions o;
  CLI::App cli{"roi-bench: reproduce the dissertation's Tests 1-3 with tables and charts"};
  bool noCharts = false;
  addOptions(cli, o, noCharts);
  try
  {
    cli.parse(argc, argv);
  }
  catch (const CLI::ParseError& e)
  {
    return cli.exit(e);
  }
  o.merge = cli.count("--merge") > 0;
  if (!o.planFile.empty() && cli.count("--tests") == 0)
    o.tests.clear();  // the plan file's tests
  o.charts = !noCharts;
  // As the SLAM apps do, so that the paired speed measurement (in this
  // process) times the pipelines as roi-graphslam runs them.
  roislam::common::tuneAllocatorForImages();
  try
  {
    roislam::bench::CBenchApp app(o);
    return app.run(std::cout, std::cerr);
  }
  catch (const std::exception& e)
  {
    std::cerr << "roi-bench: error: " << e.what() << "\n";
    return 1;
  }
}
