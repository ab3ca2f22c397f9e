/* roi-graphslam-engine end to end (the executable, with MRPT graphslam-engine's
 * command line) on a tum2rawlog rawlog of the synthetic textured loop of the
 * ctest fixture: every mode and every extractor is accurate and closes loops
 * (each combination: engine_app_slowtest); it
 * equals roi-graphslam run with the same settings in roi-graphslam's layout;
 * it prints the parameters its deciders' loadParams() read, marking the
 * defaults; MRPT's own 3-D classes run; bad input gives one-line errors. */
#include <gtest/gtest.h>
#include <roislam/testing/TestData.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "EngineRuns.h"

namespace fs = std::filesystem;
using roislam::testing::readSummary;
using roislam::testing::readText;
using roislam::testing::runEngine;
using roislam::testing::TRawlog;

namespace
{
std::string config(const std::string& name)
{
  return roislam::testing::configFile(name);
}

/** The textured loop of the fixture as a rawlog. */
const TRawlog& syntheticRawlog(const std::string& seq)
{
  return roislam::testing::rawlogOf(seq);
}

std::string writeIni(const std::string& dir, const std::string& name, const std::string& text)
{
  const std::string file = dir + "/" + name;
  std::ofstream(file) << text;
  return file;
}

/** The trajectory without its header line (which names the app). */
std::string trajectoryBody(const std::string& dir)
{
  const std::string t = readText(dir + "/trajectory.txt");
  return t.substr(t.find('\n') + 1);
}
}  // namespace

// The default suite: every mode once, every extractor once (a SIFT run is
// the slowest); one run renders the snapshot (the slow picture).
TEST(RoiGraphSlamEngineApp, SyntheticLoopInEveryModeIsAccurateAndClosesLoops)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "textured");
  const auto& data = syntheticRawlog(seq);
  const std::string out = roislam::testing::makeTempDir("engine_app_modes");
  roislam::testing::expectAccurateRun(data, out, "traditional", "sift", false);
  roislam::testing::expectAccurateRun(data, out, "roi_small", "surf", false);
  roislam::testing::expectAccurateRun(data, out, "roi_big", "orb", true);
  fs::remove_all(out);
}

TEST(RoiGraphSlamEngineApp, EqualsRoiGraphSlamOnTheSyntheticLoop)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "textured");
  const auto& data = syntheticRawlog(seq);
  const std::string out = roislam::testing::makeTempDir("engine_app_equal");
  // The same settings: config/graphslam-engine.ini is config/roi_big.ini in
  // MRPT's sections.
  const auto e = runEngine(
      "-i " + config("graphslam-engine.ini") + " -r " + data.rawlog + " -g " + data.groundTruth +
      " --output-dir " + out + "/engine --no-snapshot");
  ASSERT_EQ(e.exitCode, 0) << e.err;
  const auto g = roislam::testing::runApp(
      "roi-graphslam", "--ini " + config("roi_big.ini") + " --input " + data.rawlog +
                           " --output-dir " + out + "/roi-graphslam --no-snapshot");
  ASSERT_EQ(g.exitCode, 0) << g.err;
  const auto se = readSummary(out + "/engine"), sg = readSummary(out + "/roi-graphslam");
  for (const char* k : {"graph_nodes", "graph_edges", "keyframes", "loop_closures"})
    EXPECT_EQ(se[k], sg[k]) << k;
  EXPECT_EQ(se["ate_rmse"], sg["ate_rmse"]);
  // The same sensor description, and its camera facts used by both: neither
  // ini sets them.
  EXPECT_EQ(se["sensor"], sg["sensor"]);
  EXPECT_EQ(se["sensor"]["rolling_shutter_from"], "sensor description");
  EXPECT_NE(e.err.find("roi-graphslam-engine: "), std::string::npos);
  // One code path: the same trajectory to the last digit.
  EXPECT_EQ(trajectoryBody(out + "/engine"), trajectoryBody(out + "/roi-graphslam"));
  fs::remove_all(out);
}

TEST(RoiGraphSlamEngineApp, PrintsTheParametersItsDecidersLoaded)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "textured");
  const auto& data = syntheticRawlog(seq);
  const std::string out = roislam::testing::makeTempDir("engine_app_params");
  // A key in each of our sections; everything else on its default.
  const std::string ini = writeIni(
      out, "some.ini",
      "[GeneralConfiguration]\nclass_verbosity = 2\nmap_decimation = 6\n"
      "[NodeRegistrationDeciderParameters]\nmode = roi_small\nkeyframe_rotation_deg = 7\n"
      "rolling_shutter_ms = 25\n"
      "[FeatureExtractor]\nmax_features = 600\n"
      "[EdgeRegistrationDeciderParameters]\nloop_min_keyframe_gap = 4\n"
      "[OptimizerParameters]\noptimize_every_keyframes = 3\n");
  auto r =
      runEngine("-i " + ini + " -r " + data.rawlog + " --output-dir " + out + "/run --no-snapshot");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  for (const char* line :
       {"CKeyframeNRD parameters (ini ", "[NodeRegistrationDeciderParameters]\n",
        "\nmode = roi_small\n", "\nkeyframe_rotation_deg = 7.000000\n",
        "\nkeyframe_translation_m = 0.100000  (default)\n", "\nmap_decimation = 6\n",
        "\nmax_features = 600\n", "CKeyframeERD parameters", "\nloop_min_keyframe_gap = 4\n",
        "\nloop_min_inliers = 25  (default)\n", "CKeyframeGSO parameters",
        "\noptimize_every_keyframes = 3\n", "\noptimize_min_chi2 = 30.000000  (default)\n"})
    EXPECT_NE(r.out.find(line), std::string::npos) << line << "\n" << r.out;
  auto s = readSummary(out + "/run");
  EXPECT_EQ(s["mode"], "roi_small");
  // A readout the ini still sets overrides the sensor description's.
  EXPECT_EQ(s["sensor"]["rolling_shutter_from"], "ini");
  EXPECT_EQ(s["sensor"]["rolling_shutter_ms_used"], 25.0);
  EXPECT_FALSE(s["partial"].get<bool>());
  // An earlier output is refused before the run, untouched; --overwrite
  // replaces it (CSlamRunner stages the folder: common::COutputFolder).
  const std::string first = readText(out + "/run/summary.json");
  r = runEngine("-i " + ini + " -r " + data.rawlog + " --output-dir " + out + "/run --no-snapshot");
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("output dir " + out + "/run: not empty"), std::string::npos) << r.err;
  EXPECT_EQ(readText(out + "/run/summary.json"), first);
  r = runEngine(
      "-i " + ini + " -r " + data.rawlog + " --output-dir " + out +
      "/run --no-snapshot --overwrite");
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(fs::exists(out + "/run/report.txt"));
  // Without ground truth: no ATE, no RPE.
  EXPECT_TRUE(s["ate_rmse"].is_null());
  EXPECT_TRUE(s["rpe_trans_rmse"].is_null());
  // The reports carry the same parameters.
  const std::string report = readText(out + "/run/report.txt");
  EXPECT_NE(report.find("\nkeyframe_rotation_deg = 7.000000\n"), std::string::npos);
  EXPECT_NE(
      report.find("Num of Nodes: " + std::to_string(s["graph_nodes"].get<int>())),
      std::string::npos);

  // An ini without any of the sections runs on the defaults and lists them.
  const std::string empty = writeIni(out, "empty.ini", "# nothing here\n");
  r = runEngine(
      "-i " + empty + " -r " + data.rawlog + " -g " + data.groundTruth + " --output-dir " + out +
      "/defaults --no-snapshot");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  for (const char* line :
       {"\nmode = traditional  (default)\n", "\nfeature_type = orb  (default)\n",
        "\nloop_min_keyframe_gap = 10  (default)\n",
        "\noptimize_window_keyframes = 50  (default)\n",
        "\nedge_information = estimator  (default)\n"})
    EXPECT_NE(r.out.find(line), std::string::npos) << line << "\n" << r.out;
  s = readSummary(out + "/defaults");
  EXPECT_EQ(s["mode"], "traditional");
  EXPECT_EQ(s["tracked_frames"], s["frames"]);
  EXPECT_FALSE(s["ate_rmse"].is_null());
  fs::remove_all(out);
}

TEST(RoiGraphSlamEngineApp, RunsMrptsOwnDecidersThatWorkInThreeD)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "textured");
  const auto& data = syntheticRawlog(seq);
  const std::string out = roislam::testing::makeTempDir("engine_app_mrpt");
  const std::string base = "-i " + config("graphslam-engine.ini") + " -r " + data.rawlog + " -g " +
                           data.groundTruth + " --no-snapshot --output-dir " + out;
  // Odometry only: MRPT's empty edge decider, our optimiser.
  auto r = runEngine(base + "/empty -e CEmptyERD");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  auto s = readSummary(out + "/empty");
  EXPECT_EQ(s["engine"]["edge_registration_decider"], "CEmptyERD");
  EXPECT_EQ(s["loop_closures"].get<int>(), 0);
  EXPECT_EQ(s["graph_edges"].get<int>(), s["graph_nodes"].get<int>() - 1);
  EXPECT_EQ(s["tracked_frames"], s["frames"]);
  // MRPT's optimiser on our edges (its optimised poses are kept too).
  r = runEngine(base + "/levmarq -o CLevMarqGSO");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  s = readSummary(out + "/levmarq");
  EXPECT_EQ(s["engine"]["optimizer"], "CLevMarqGSO");
  EXPECT_GE(s["loop_closures"].get<int>(), 1);
  EXPECT_TRUE(s["optimizations"].is_null());
  EXPECT_TRUE(s["final_optimization"].is_null());
  EXPECT_LT(s["ate_rmse"].get<double>(), 0.05);
  fs::remove_all(out);
}

TEST(RoiGraphSlamEngineApp, BadInputGivesOneLineErrors)
{
  const std::string out = roislam::testing::makeTempDir("engine_app_bad");
  const std::string ini = config("graphslam-engine.ini");
  const std::string rawlog = [&]() -> std::string
  {
    const auto seq = roislam::testing::syntheticSequence("textured");
    return seq ? syntheticRawlog(*seq).rawlog : out + "/none.rawlog";
  }();
  const auto expectError = [&](const std::string& args, const std::string& text)
  {
    const auto r = runEngine(args + " --output-dir " + out + "/run --no-snapshot");
    EXPECT_EQ(r.exitCode, 1) << args;
    EXPECT_EQ(r.err.rfind("roi-graphslam-engine: error: ", 0), 0u) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
    EXPECT_NE(r.err.find(text), std::string::npos) << args << ": " << r.err;
  };
  // Refused names; MRPT's ICP and loop-closer deciders are 2-D only: refused
  // with --3d (and without: 3-D is the default).
  const std::string base = "-i " + ini + " -r " + rawlog + " --3d ";
  for (const auto& [args, text] : std::vector<std::pair<std::string, std::string>>{
           {"-n CNoSuchNRD", "-n/--node-reg CNoSuchNRD: unknown"},
           {"-e CICPCriteriaERD", "-e/--edge-reg CICPCriteriaERD: works on 2-D graphs only"},
           {"-n CICPCriteriaNRD", "-n/--node-reg CICPCriteriaNRD: works on 2-D graphs only"},
           {"-e CLoopCloserERD", "-e/--edge-reg CLoopCloserERD: works on 2-D graphs only"},
           {"-n CFixedIntervalsNRD", "CFixedIntervalsNRD: registers nodes from odometry"},
           {"-o CEmptyGSO", "CEmptyGSO: abstract"}})
    expectError(base + args, text);
  expectError("-i " + ini + " -r " + rawlog + " --2d", "--2d: roi-graphslam-engine builds 3-D");
  expectError("-i " + ini + " -r /nonexistent/x.rawlog", "/nonexistent/x.rawlog");
  expectError("-i /nonexistent.ini -r " + rawlog, "ini /nonexistent.ini: cannot open");
  expectError("-i " + ini, "-r/--rawlog is required");
  expectError("-i " + ini + " -r " + rawlog + " -g /nonexistent/gt.txt", "/nonexistent/gt.txt");
  // Strict reading (common::CStrictIniFile) of MRPT's sections too, the
  // deciders' included: MRPT alone runs on the defaults or keeps the last.
  const std::string broken = writeIni(out, "broken.ini", "[this is not\n");
  expectError("-i " + broken + " -r " + rawlog, broken + ":1: malformed section header");
  const std::string twice = writeIni(
      out, "twice.ini",
      "[EdgeRegistrationDeciderParameters]\nloop_min_inliers = 30\nloop_min_inliers = 40\n");
  expectError(
      "-i " + twice + " -r " + rawlog,
      twice + ":3: duplicate key 'loop_min_inliers' (first given on line 2)");
  const std::string garbage =
      writeIni(out, "garbage.ini", "[OptimizerParameters]\noptimize_every_keyframes 3\n");
  expectError(
      "-i " + garbage + " -r " + rawlog,
      garbage + ":2: expected a comment, [section] or key = value");
  const std::string second =
      writeIni(out, "second.ini", "[OptimizerParameters]\noptimization_on_second_thread = true\n");
  expectError(
      "-i " + second + " -r " + rawlog + " -o CLevMarqGSO",
      "[OptimizerParameters] optimization_on_second_thread: must be false");
  if (!fs::exists(rawlog))
    return;  // the remaining errors come from the deciders' loadParams()
  const std::string bad =
      writeIni(out, "bad.ini", "[NodeRegistrationDeciderParameters]\nkeyframe_rotation_deg = -1\n");
  expectError(
      "-i " + bad + " -r " + rawlog,
      "ini " + bad + ": [NodeRegistrationDeciderParameters] keyframe_rotation_deg: must be > 0");
  const std::string badLoop =
      writeIni(out, "badloop.ini", "[EdgeRegistrationDeciderParameters]\nloop_min_inliers = 2\n");
  expectError(
      "-i " + badLoop + " -r " + rawlog,
      "[EdgeRegistrationDeciderParameters] loop_min_inliers: must be >= 3");
  const std::string unknown =
      writeIni(out, "unknown.ini", "[OptimizerParameters]\noptimize_every_keyframe = 3\n");
  expectError(
      "-i " + unknown + " -r " + rawlog,
      "[OptimizerParameters] unknown key 'optimize_every_keyframe'");
  const std::string mixed = writeIni(
      out, "mixed.ini",
      "[FrontEnd]\nmode = roi_big\n[OptimizerParameters]\nloop_outlier_chi2 = 9\n");
  expectError(
      "-i " + mixed + " -r " + rawlog,
      "[OptimizerParameters] loop_outlier_chi2: this ini uses roi-graphslam's sections");
  fs::remove_all(out);
}

TEST(RoiGraphSlamEngineApp, ListsTheClassesAndWhyOthersAreRefused)
{
  const auto r = runEngine("--list-regs --list-optimizers");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  for (const char* text :
       {"CKeyframeNRD: ", "CKeyframeERD: ", "CKeyframeGSO: ", "CEmptyERD: ", "CLevMarqGSO: ",
        "not usable here:\n", "CICPCriteriaNRD: works on 2-D graphs only"})
    EXPECT_NE(r.out.find(text), std::string::npos) << text << "\n" << r.out;
}
