/* roi-eval: ATE and RPE of an estimated TUM trajectory against ground truth,
 * with the semantics of the TUM RGB-D benchmark scripts (CTrajectoryEvaluator). */
#include <roislam/evaluation/CEvalApp.h>

#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <string>

int main(int argc, char** argv)
{
  using roislam::evaluation::CEvalApp;
  CEvalApp::TParams p;
  std::string unit = "s";
  CLI::App cli{
      "roi-eval: absolute trajectory error (ATE) and relative pose error (RPE) of an "
      "estimated trajectory, as the TUM RGB-D benchmark's evaluate_ate.py and "
      "evaluate_rpe.py --fixed_delta compute them"};
  cli.add_option("--gt", p.groundTruthFile, "ground truth (TUM: timestamp tx ty tz qx qy qz qw)")
      ->required();
  cli.add_option("--est", p.estimateFile, "estimated trajectory (TUM format)")->required();
  cli.add_option(
         "--max-difference", p.evaluation.max_difference,
         "max |t_gt - (t_est + offset)| for ATE association, s")
      ->capture_default_str();
  cli.add_option("--offset", p.evaluation.offset, "time offset added to estimate stamps, s")
      ->capture_default_str();
  cli.add_option("--delta", p.evaluation.delta, "RPE pair distance (in --delta-unit)")
      ->capture_default_str();
  cli.add_option("--delta-unit", unit, "RPE delta unit: s (seconds) or f (frames)")
      ->check(CLI::IsMember({"s", "f"}))
      ->capture_default_str();
  cli.add_flag("--json", p.json, "print one JSON object instead of a table");
  cli.add_option("--plot", p.plotFile, "write a PNG: ground truth and aligned estimate");
  cli.add_option("--plot-errors", p.errorPlotFile, "write a PNG: ATE and RPE over time");
  cli.add_option("--save-aligned", p.alignedFile, "write the aligned estimate (TUM format)");
  cli.add_flag(
      "--skip-invalid", p.skipInvalid,
      "skip lines with a NaN or a zero quaternion, as the benchmark scripts do (default: error)");
  cli.add_option(
      "--graph", p.graphFile,
      "also check a run's graph.graph against the ground truth: each edge's chi-square "
      "(needs --frames)");
  cli.add_option(
      "--frames", p.framesFile, "the same run's frames.csv (which frame each graph node is)");
  CLI11_PARSE(cli, argc, argv);

  try
  {
    p.evaluation.delta_unit = roislam::evaluation::deltaUnitFromString(unit);
    const auto result = CEvalApp(p).run(std::cout);
    if (const std::string w = roislam::evaluation::mirrorWarning(result.ate); !w.empty())
      std::cerr << "roi-eval: " << w << "\n";
    return 0;
  }
  catch (const std::exception& e)
  {
    // MRPT exceptions append a call stack after the first line.
    const std::string what = e.what();
    std::cerr << "roi-eval: error: " << what.substr(0, what.find('\n')) << "\n";
    return 1;
  }
}
