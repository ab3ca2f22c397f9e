/* Test helpers of the roi-graphslam-engine tests (engine_app_*, engine_tum_*):
 * config/graphslam-engine.ini (mode roi_big, ORB) in another mode and with
 * another extractor, as roi-graphslam's --mode / --feature would set them;
 * the synthetic loop and the shared fr1 excerpts as tum2rawlog rawlogs (made
 * once per test program); a run of the app on the synthetic loop with its
 * checks; the comparison of the two apps on a shared excerpt. */
#pragma once

#include <gtest/gtest.h>
#include <roislam/common/ProcessTuning.h>
#include <roislam/graphslam/CRoiGraphSlamApp.h>
#include <roislam/graphslam/CRoiGraphSlamEngineApp.h>
#include <roislam/io/CTum2RawlogApp.h>
#include <roislam/testing/TestData.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace roislam::testing
{
inline std::string configFile(const std::string& name)
{
  return sourceDir() + "/config/" + name;
}

inline std::string readText(const std::string& file)
{
  std::ifstream f(file);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

/** Writes <dir>/engine-<mode>-<feature>.ini and returns its path. */
inline std::string engineIniVariant(
    const std::string& dir, const std::string& mode, const std::string& feature)
{
  std::string text = std::regex_replace(
      readText(configFile("graphslam-engine.ini")), std::regex("\nmode = roi_big\n"),
      "\nmode = " + mode + "\n");
  text = std::regex_replace(
      text, std::regex("\nfeature_type = orb\n"), "\nfeature_type = " + feature + "\n");
  const std::string file = dir + "/engine-" + mode + "-" + feature + ".ini";
  std::ofstream(file) << text;
  return file;
}

/** A tum2rawlog rawlog and the ground truth written next to it. */
struct TRawlog
{
  std::string rawlog, groundTruth;
};

/** The TUM folder `folder` as a rawlog in a folder removed at exit, made once
 *  per test program. */
inline const TRawlog& rawlogOf(const std::string& folder, const std::string& camera = "auto")
{
  static std::map<std::string, TRawlog> made;
  static const CTempDir dir("engine_rawlog");
  auto it = made.find(folder);
  if (it == made.end())
  {
    io::CTum2RawlogApp::TOptions o;
    o.input = folder;
    o.output = dir.path() + "/" + std::to_string(made.size()) + ".rawlog";
    o.camera = camera;
    const auto r = io::CTum2RawlogApp(o).run();
    it = made.emplace(folder, TRawlog{r.rawlog, r.groundTruth.value_or("")}).first;
  }
  return it->second;
}

inline TAppRun runEngine(const std::string& args)
{
  return runApp("roi-graphslam-engine", args);
}

inline nlohmann::json readSummary(const std::string& dir)
{
  std::ifstream f(dir + "/summary.json");
  return nlohmann::json::parse(f);
}

/** The app on the synthetic loop `data` in `mode` with `feature`: every
 *  frame tracked, ATE < 1 cm, RPE from -g, at least one loop closure, every
 *  output written (snapshot.png when `snapshot`). */
inline void expectAccurateRun(
    const TRawlog& data, const std::string& out, const std::string& mode,
    const std::string& feature, bool snapshot)
{
  const std::string dir = out + "/" + mode + "-" + feature;
  const auto r = runEngine(
      "-i " + engineIniVariant(out, mode, feature) + " -r " + data.rawlog + " -g " +
      data.groundTruth + " --3d --disable-visuals --output-dir " + dir +
      (snapshot ? "" : " --no-snapshot"));
  ASSERT_EQ(r.exitCode, 0) << mode << " " << feature << ": " << r.err;
  const auto s = readSummary(dir);
  std::printf(
      "%-12s %-5s ATE %.4f m, %d keyframes, %d loop closures\n", mode.c_str(), feature.c_str(),
      s["ate_rmse"].get<double>(), s["keyframes"].get<int>(), s["loop_closures"].get<int>());
  EXPECT_EQ(s["mode"], mode);
  EXPECT_EQ(s["feature"], feature);
  EXPECT_EQ(s["tracked_frames"], s["frames"]) << mode << " " << feature;
  EXPECT_LT(s["ate_rmse"].get<double>(), 0.01) << mode << " " << feature;
  // -g: the TUM ground truth gives the RPE too.
  EXPECT_GT(s["rpe_trans_rmse"].get<double>(), 0.0) << mode << " " << feature;
  EXPECT_LT(s["rpe_trans_rmse"].get<double>(), 0.05) << mode << " " << feature;
  EXPECT_GE(s["rpe_rot_rmse_deg"].get<double>(), 0.0) << mode << " " << feature;
  EXPECT_GE(s["loop_closures"].get<int>(), 1) << mode << " " << feature;
  EXPECT_EQ(s["engine"]["node_registration_decider"], "CKeyframeNRD");
  std::vector<std::string> files{"trajectory.txt", "graph.graph", "map.bt",
                                 "frames.csv",     "report.txt",  "summary.json"};
  if (snapshot)
    files.push_back("snapshot.png");
  for (const auto& f : files)
    EXPECT_TRUE(std::filesystem::exists(dir + "/" + f)) << dir << "/" << f;
}

/** The shared excerpt `name` (tum/<name> of the shared data), or nullopt. */
inline std::optional<TRawlog> sharedExcerpt(const std::string& name)
{
  const std::filesystem::path folder = std::filesystem::path(sharedDataDir()) / "tum" / name;
  if (!std::filesystem::exists(folder / "rgb.txt"))
    return std::nullopt;
  return rawlogOf(folder.string(), "fr1");
}

/** roi-graphslam (config/<mode>.ini, its own layout, --feature) and
 *  roi-graphslam-engine (config/graphslam-engine.ini in `mode` with
 *  `feature`) on the rawlog of the shared excerpt `name`: the same node,
 *  edge and loop-closure counts and an ATE within 2 %. */
inline void expectEngineEqualsRoiGraphSlam(
    const std::string& name, const std::string& mode, const std::string& feature)
{
  const auto seq = sharedExcerpt(name);
  ASSERT_TRUE(seq);
  common::tuneAllocatorForImages();
  const std::string dir = makeTempDir("engine_tum_" + mode + "_" + feature);

  graphslam::CRoiGraphSlamApp::TArguments g;
  g.iniFile = configFile(mode + ".ini");
  g.input = seq->rawlog;
  g.outputDir = dir + "/roi-graphslam";
  g.feature = feature;
  g.snapshot = false;
  const auto a = graphslam::CRoiGraphSlamApp(g).run();

  graphslam::CRoiGraphSlamEngineApp::TArguments e;
  e.iniFile = engineIniVariant(dir, mode, feature);
  e.rawlog = seq->rawlog;
  e.groundTruth = seq->groundTruth;
  e.outputDir = dir + "/engine";
  e.snapshot = false;
  const auto b = graphslam::CRoiGraphSlamEngineApp(e).run();

  ASSERT_TRUE(a.ateRmse && b.ateRmse);
  std::printf(
      "%s %-12s %-5s ATE roi-graphslam %.5f m, engine %.5f m; nodes %zu / %zu, edges %zu / %zu\n",
      name.c_str(), mode.c_str(), feature.c_str(), *a.ateRmse, *b.ateRmse, a.graphNodes,
      b.graphNodes, a.graphEdges, b.graphEdges);
  EXPECT_EQ(a.graphNodes, b.graphNodes);
  EXPECT_EQ(a.graphEdges, b.graphEdges);
  EXPECT_EQ(a.loopClosures, b.loopClosures);
  EXPECT_NEAR(*b.ateRmse, *a.ateRmse, 0.02 * *a.ateRmse);
  std::filesystem::remove_all(dir);
}
}  // namespace roislam::testing
