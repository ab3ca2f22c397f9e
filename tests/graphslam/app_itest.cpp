/* roi-graphslam end to end (the executable, as users run it) on the
 * synthetic sequences of the ctest fixture and on bad input. */
#include <gtest/gtest.h>
#include <roislam/io/GraphText.h>
#include <roislam/testing/TestData.h>

#include <Eigen/Cholesky>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace
{
roislam::testing::TAppRun runApp(const std::string& args)
{
  return roislam::testing::runApp("roi-graphslam", args);
}

nlohmann::json readSummary(const std::string& dir)
{
  std::ifstream f(dir + "/summary.json");
  return nlohmann::json::parse(f);
}

std::string config(const std::string& name)
{
  return roislam::testing::sourceDir() + "/config/" + name;
}
}  // namespace

TEST(RoiGraphSlamApp, TexturedLoopIsAccurateAndClosesLoops)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "textured");
  const std::string out = roislam::testing::makeTempDir("gs_textured");
  const auto r =
      runApp("--ini " + config("traditional.ini") + " --input " + seq + " --output-dir " + out);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  for (const char* f :
       {"trajectory.txt", "graph.graph", "map.bt", "scene.3Dscene", "snapshot.png", "frames.csv",
        "summary.json"})
    EXPECT_TRUE(fs::exists(out + "/" + f)) << f;
  const auto s = readSummary(out);
  EXPECT_EQ(s["tracked_frames"], s["frames"]);
  EXPECT_GE(s["loop_closures"].get<int>(), 1);
  ASSERT_FALSE(s["ate_rmse"].is_null());
  EXPECT_LT(s["ate_rmse"].get<double>(), 0.01);
  EXPECT_FALSE(s["failed"].get<bool>());
  // The graph's a-posteriori variance factor (CSlamContext::varianceFactor),
  // at least 1, and the loop-outlier test's scale, at least that
  // (CSlamContext::loopVarianceFactor: the closures' own when larger).
  ASSERT_TRUE(s["final_optimization"].is_object());
  const double graphFactor = s["final_optimization"]["variance_factor"].get<double>();
  EXPECT_GE(graphFactor, 1.0);
  EXPECT_GE(s["final_optimization"]["loop_variance_factor"].get<double>(), graphFactor);

  // graph.graph opens in MRPT's own graph-slam tool (mrpt-apps), without a
  // display: --info loads it and counts nodes and edges.
#ifdef ROISLAM_MRPT_GRAPH_SLAM_TOOL
  const std::string info = out + "/graph_info.txt";
  const int rc = std::system((std::string(ROISLAM_MRPT_GRAPH_SLAM_TOOL) + " --info --3d -i " + out +
                              "/graph.graph > " + info + " 2>&1")
                                 .c_str());
  ASSERT_EQ(rc, 0);
  std::ifstream in(info);
  std::string line;
  int nodes = -1, edges = -1;
  while (std::getline(in, line))
  {
    const auto colon = line.find(':');
    if (colon == std::string::npos)
      continue;
    if (line.rfind("Edge count", 0) == 0)
      edges = std::stoi(line.substr(colon + 1));
    else if (line.rfind("Nodes count (in VERTEX2/3 entries)", 0) == 0)
      nodes = std::stoi(line.substr(colon + 1));
  }
  EXPECT_EQ(nodes, s["graph_nodes"].get<int>());
  EXPECT_EQ(edges, s["graph_edges"].get<int>());
#endif
  // Read back whole (GraphText.h): every edge's information is positive
  // definite, as the run's own was.
  const auto g = roislam::io::loadGraphText(out + "/graph.graph");
  EXPECT_EQ(g.nodes.size(), s["graph_nodes"].get<std::size_t>());
  EXPECT_EQ(g.edges.size(), s["graph_edges"].get<std::size_t>());
  for (const auto& [ids, e] : g.edges)
    EXPECT_EQ(e.cov_inv.asEigen().llt().info(), Eigen::Success)
        << "edge " << ids.first << "-" << ids.second;

  // roi-eval checks the saved graph against the ground truth after the run
  // and reads what the run read (summary.json's edge_chi2).
  const std::string gt = seq + "/groundtruth.txt";
  const auto ev = roislam::testing::runApp(
      "roi-eval", "--gt " + gt + " --est " + out + "/trajectory.txt --graph " + out +
                      "/graph.graph --frames " + out + "/frames.csv --json");
  ASSERT_EQ(ev.exitCode, 0) << ev.err;
  const auto j = nlohmann::json::parse(ev.out);
  ASSERT_TRUE(j["edge_chi2"].is_object()) << ev.out;
  const auto& online = s["edge_chi2"];
  EXPECT_EQ(j["edge_chi2"]["edges"], online["edges"]);
  // frames.csv keeps times to the microsecond.
  for (const char* k : {"median", "mean"})
    EXPECT_NEAR(
        j["edge_chi2"][k].get<double>(), online[k].get<double>(), 1e-3 * online[k].get<double>())
        << k;
  const auto bad = roislam::testing::runApp(
      "roi-eval",
      "--gt " + gt + " --est " + out + "/trajectory.txt --graph " + out + "/graph.graph");
  EXPECT_EQ(bad.exitCode, 1);
  EXPECT_NE(bad.err.find("--graph and --frames go together"), std::string::npos) << bad.err;
  fs::remove_all(out);
}

TEST(RoiGraphSlamApp, FeaturelessTrackedByFallbackButStrictRoiFails)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "featureless");
  const std::string out = roislam::testing::makeTempDir("gs_featureless");
  auto r = runApp(
      "--ini " + config("roi_big.ini") + " --input " + seq + " --output-dir " + out +
      " --no-snapshot");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  auto s = readSummary(out);
  EXPECT_EQ(s["tracked_frames"], s["frames"]);
  EXPECT_EQ(s["lost_frames"].get<int>(), 0);
  EXPECT_GT(s["fallback_frames"].get<int>(), 0);

  // The dissertation's behaviour: ROI without fallback loses the featureless wall.
  r = runApp(
      "--ini " + config("roi_big.ini") + " --input " + seq + " --output-dir " + out +
      " --no-snapshot --strict-roi --overwrite");
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("tracking failed"), std::string::npos) << r.err;
  s = readSummary(out);
  EXPECT_TRUE(s["failed"].get<bool>());
  EXPECT_GT(s["lost_frames"].get<int>(), 0);
  fs::remove_all(out);
}

TEST(RoiGraphSlamApp, BadInputAndIniGiveOneLineErrors)
{
  const std::string out = roislam::testing::makeTempDir("gs_bad");
  auto r = runApp("--input /nonexistent/seq --output-dir " + out);
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_EQ(r.err.rfind("roi-graphslam: error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("/nonexistent/seq"), std::string::npos) << r.err;

  const std::string ini = out + "/bad.ini";
  {
    std::ofstream f(ini);
    f << "[GraphSlam]\nloop_min_keyframe_gapp = 4\n";
  }
  r = runApp("--ini " + ini + " --input /nonexistent/seq --output-dir " + out);
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(
      r.err.find("ini " + ini + ": [GraphSlam] unknown key 'loop_min_keyframe_gapp'"),
      std::string::npos)
      << r.err;
  {
    std::ofstream f(ini);
    f << "[FrontEnd]\nmode = traditional\nfoo = 1\n";
  }
  r = runApp("--ini " + ini + " --input /nonexistent/seq --output-dir " + out);
  EXPECT_NE(r.err.find("[FrontEnd] unknown key 'foo'"), std::string::npos) << r.err;

  r = runApp("--ini /nonexistent.ini --input x --output-dir " + out);
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("ini /nonexistent.ini: cannot open"), std::string::npos) << r.err;

  // Unwritable output folder (a path below a regular file), valid input.
  if (const auto seq = roislam::testing::syntheticSequence("featureless"))
  {
    r = runApp("--input " + *seq + " --output-dir " + ini + "/sub");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("output dir " + ini + "/sub"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  fs::remove_all(out);
}

TEST(RoiGraphSlamApp, ListsOurDecidersByName)
{
  const std::string exe = roislam::testing::binaryDir() + "/apps/roi-graphslam/roi-graphslam";
  FILE* p = popen((exe + " --list-node-regs --list-edge-regs").c_str(), "r");
  ASSERT_TRUE(p);
  std::string text;
  char buf[512];
  while (fgets(buf, sizeof buf, p))
    text += buf;
  EXPECT_EQ(pclose(p), 0);
  EXPECT_NE(text.find("CKeyframeNRD: "), std::string::npos) << text;
  EXPECT_NE(text.find("CKeyframeERD: "), std::string::npos) << text;
}
