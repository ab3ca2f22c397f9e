#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <roislam/bench/CExperimentPlan.h>
#include <roislam/testing/TestData.h>

#include <algorithm>
#include <filesystem>
#include <set>

#include "FakeApps.h"

using namespace roislam::bench;
namespace fs = std::filesystem;

namespace
{
std::vector<TSequence> twoSequences()
{
  return {{"seqA", "/data/seqA", true}, {"seq B", "/data/seq B", true}};
}

CExperimentPlan::TLocations locations()
{
  CExperimentPlan::TLocations loc;
  loc.executables = {
      {"roi-landmarks", "/bin/lm"}, {"roi-graphslam", "/bin/gs"}, {"cv-odometry", "/bin/cv"}};
  loc.configDir = "/cfg";
  loc.outputDir = "/out";
  return loc;
}

std::size_t countTest(const std::vector<TBenchRun>& runs, int test)
{
  return std::count_if(
      runs.begin(), runs.end(), [&](const TBenchRun& r) { return r.test == test; });
}
}  // namespace

TEST(CExperimentPlan, countsPerTest)
{
  const auto runs = CExperimentPlan({}, locations()).build(twoSequences());
  // Test 1: 2 seq x 3 features x (plain + hue). Test 2: 2 x 3 features x (traditional + 2
  // ROI modes x 5 variants). Test 3: 2 x (traditional + big ROI x 5 variants). No Test 4.
  EXPECT_EQ(countTest(runs, 1), 12u);
  EXPECT_EQ(countTest(runs, 4), 0u);
  EXPECT_EQ(countTest(runs, 2), 66u);
  EXPECT_EQ(countTest(runs, 3), 12u);
  // Reference rows: 2 seq x cv-odometry rgbd, icp, rgbdicp.
  EXPECT_EQ(countTest(runs, 0), 6u);
  std::set<std::string> ids;
  for (const auto& r : runs)
    ids.insert(r.id);
  EXPECT_EQ(ids.size(), runs.size()) << "run ids must be unique";
}

TEST(CExperimentPlan, countsWithoutVariantsAndSelectedTests)
{
  CExperimentPlan::TOptions o;
  o.variants.clear();
  o.tests = {2, 3};
  const auto runs = CExperimentPlan(o, locations()).build(twoSequences());
  EXPECT_EQ(countTest(runs, 1), 0u);
  EXPECT_EQ(countTest(runs, 2), 18u);
  EXPECT_EQ(countTest(runs, 3), 4u);
}

TEST(CExperimentPlan, test1HueVariantAndTest4)
{
  CExperimentPlan::TOptions o;
  o.tests = {1, 4};
  const auto runs = CExperimentPlan(o, locations()).build(twoSequences());
  const auto find = [&](const std::string& id)
  {
    const auto it =
        std::find_if(runs.begin(), runs.end(), [&](const TBenchRun& r) { return r.id == id; });
    EXPECT_NE(it, runs.end()) << id;
    return it == runs.end() ? TBenchRun() : *it;
  };
  const auto hue = find("t1-seqA-orb-hue");
  EXPECT_EQ(hue.iniFile, "/out/configs/roi_landmarks-hue.ini");
  EXPECT_EQ(hue.baseIni, "/cfg/roi_landmarks.ini");
  ASSERT_EQ(hue.iniOverrides.size(), 1u);
  EXPECT_EQ(hue.iniOverrides[0].key, "verify_hue");
  // Test 4: per sequence and extractor the EKF run and the graph SLAM run.
  EXPECT_EQ(countTest(runs, 4), 12u);
  const auto ekf = find("t4-seq_B-kf_slam-sift");
  EXPECT_EQ(
      ekf.argv,
      (std::vector<std::string>{
          "/bin/lm", "--ini", "/cfg/roi_landmarks.ini", "--input", "/data/seq B", "--output-dir",
          "/out/runs/t4-seq_B-kf_slam-sift/output", "--kf-slam", "--feature", "sift"}));
  const auto graph = find("t4-seqA-graph_slam-orb");
  EXPECT_EQ(
      graph.argv, (std::vector<std::string>{
                      "/bin/gs", "--ini", "/cfg/roi_big.ini", "--input", "/data/seqA",
                      "--output-dir", "/out/runs/t4-seqA-graph_slam-orb/output", "--mode",
                      "roi_big", "--feature", "orb", "--no-snapshot"}));
}

TEST(CExperimentPlan, commandLines)
{
  const auto runs = CExperimentPlan({}, locations()).build(twoSequences());
  const auto it = std::find_if(
      runs.begin(), runs.end(),
      [](const TBenchRun& r) { return r.id == "t2-seq_B-roi_big-sift-600-strict"; });
  ASSERT_NE(it, runs.end());
  const std::vector<std::string> expected{
      "/bin/gs",
      "--ini",
      "/out/configs/roi_big-strict.ini",
      "--input",
      "/data/seq B",
      "--output-dir",
      "/out/runs/t2-seq_B-roi_big-sift-600-strict/output",
      "--mode",
      "roi_big",
      "--feature",
      "sift",
      "--max-features",
      "600",
      "--no-snapshot"};
  EXPECT_EQ(it->argv, expected);
  EXPECT_EQ(it->baseIni, "/cfg/roi_big.ini");

  const auto t1 = std::find_if(
      runs.begin(), runs.end(), [](const TBenchRun& r) { return r.id == "t1-seqA-orb"; });
  ASSERT_NE(t1, runs.end());
  const std::vector<std::string> e1{
      "/bin/lm",    "--ini",        "/cfg/roi_landmarks.ini",       "--input",
      "/data/seqA", "--output-dir", "/out/runs/t1-seqA-orb/output", "--feature",
      "orb"};
  EXPECT_EQ(t1->argv, e1);

  const auto t3 = std::find_if(
      runs.begin(), runs.end(),
      [](const TBenchRun& r) { return r.id == "t3-seqA-traditional-surf-50"; });
  ASSERT_NE(t3, runs.end());
  EXPECT_EQ(t3->argv[2], "/cfg/traditional.ini");
  EXPECT_NE(std::find(t3->argv.begin(), t3->argv.end(), "50"), t3->argv.end());

  const auto ref = std::find_if(
      runs.begin(), runs.end(), [](const TBenchRun& r) { return r.id == "ref-seq_B-cv_icp"; });
  ASSERT_NE(ref, runs.end());
  EXPECT_EQ(ref->test, 0);
  EXPECT_EQ(ref->app, "cv-odometry");
  const std::vector<std::string> eref{
      "/bin/cv",  "--input", "/data/seq B", "--output-dir", "/out/runs/ref-seq_B-cv_icp/output",
      "--method", "icp"};
  EXPECT_EQ(ref->argv, eref);
}

TEST(CExperimentPlan, referenceMethodsFromIni)
{
  mrpt::config::CConfigFileMemory cfg;
  cfg.write("Bench", "reference_methods", "rgbdicp");
  CExperimentPlan::TOptions o;
  o.loadFromConfigFile(cfg, "Bench");
  EXPECT_EQ(o.reference_methods, std::vector<std::string>{"rgbdicp"});
  cfg.write("Bench", "reference_methods", "none");
  o.loadFromConfigFile(cfg, "Bench");
  EXPECT_TRUE(o.reference_methods.empty());
  EXPECT_EQ(countTest(CExperimentPlan(o, locations()).build(twoSequences()), 0), 0u);
  // Round trip: "none" is written for an empty list and reads back as empty.
  mrpt::config::CConfigFileMemory saved;
  o.saveToConfigFile(saved, "Bench");
  CExperimentPlan::TOptions back;
  back.loadFromConfigFile(saved, "Bench");
  EXPECT_TRUE(back.reference_methods.empty());
  cfg.write("Bench", "reference_methods", "rgbd,fovis");
  try
  {
    o.loadFromConfigFile(cfg, "Bench");
    FAIL() << "expected an exception";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("[Bench] reference_methods"), std::string::npos)
        << e.what();
  }
}

TEST(CExperimentPlan, optionsFromIniAndBadKeys)
{
  mrpt::config::CConfigFileMemory cfg;
  cfg.write("Bench", "tests", "1,3");
  cfg.write("Bench", "test3_max_features", 25);
  CExperimentPlan::TOptions o;
  o.loadFromConfigFile(cfg, "Bench");
  EXPECT_EQ(o.tests, (std::set<int>{1, 3}));
  EXPECT_EQ(o.test3_max_features, 25);

  cfg.write("Bench", "features", "surf,brisk");
  try
  {
    o.loadFromConfigFile(cfg, "Bench");
    FAIL() << "expected an exception";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("[Bench] features"), std::string::npos) << e.what();
  }
  EXPECT_THROW(CExperimentPlan::parseTests("1,5"), std::invalid_argument);
  EXPECT_EQ(CExperimentPlan::parseTests("4"), std::set<int>{4});
}

TEST(TVariant, parseAndApplyOverrides)
{
  const auto v = TVariant::parse("nohue:FrontEnd.strict_roi=true,Roi.use_hue = false");
  EXPECT_EQ(v.name, "nohue");
  ASSERT_EQ(v.overrides.size(), 2u);
  EXPECT_EQ(v.overrides[1].section, "Roi");
  EXPECT_EQ(v.overrides[1].key, "use_hue");
  EXPECT_EQ(v.overrides[1].value, "false");
  EXPECT_THROW(TVariant::parse("bad"), std::invalid_argument);
  EXPECT_THROW(TVariant::parse("x:novalue"), std::invalid_argument);
  EXPECT_THROW(TVariant::parse("a-b:S.k=v"), std::invalid_argument);

  const std::string ini =
      "; comment\n[FrontEnd]\nfeature = surf\nstrict_roi = false\n\n[Other]\nx = 1\n";
  const std::string out = applyIniOverrides(
      ini, {{"FrontEnd", "strict_roi", "true"}, {"Other", "y", "2"}, {"New", "z", "3"}});
  EXPECT_EQ(
      out,
      "; comment\n[FrontEnd]\nfeature = surf\nstrict_roi = true\n\n[Other]\nx = 1\ny = 2\n[New]\n"
      "z = 3\n");
}

TEST(CExperimentPlan, discoverSequencesAndWriteVariantConfigs)
{
  const std::string tmp = roislam::testing::makeTempDir("bench_plan");
  fake::makeFakeSequence(tmp + "/all", "b_seq");
  fake::makeFakeSequence(tmp + "/all", "a_seq");
  const std::string single = fake::makeFakeSequence(tmp + "/other", "a_seq");
  const auto seqs = CExperimentPlan::discoverSequences({tmp + "/all", single});
  ASSERT_EQ(seqs.size(), 3u);
  EXPECT_EQ(seqs[0].name, "a_seq");
  EXPECT_EQ(seqs[1].name, "b_seq");
  EXPECT_EQ(seqs[2].name, "a_seq_2");
  EXPECT_TRUE(seqs[0].hasGroundTruth);
  EXPECT_THROW(CExperimentPlan::discoverSequences({tmp + "/nothing"}), std::runtime_error);

  // 7-Scenes' own layout: a sequence named by its scene (every scene has a
  // seq-01), with ground truth when it has poses.
  for (const char* scene : {"chess", "fire"})
  {
    const fs::path seq = fs::path(tmp) / "7scenes" / scene / "seq-01";
    fs::create_directories(seq);
    for (const char* f : {"frame-000000.color.png", "frame-000000.depth.png"})
      std::ofstream(seq / f) << "x";
    if (std::string(scene) == "chess")
      std::ofstream(seq / "frame-000000.pose.txt") << "1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n";
  }
  const auto seven =
      CExperimentPlan::discoverSequences({tmp + "/7scenes/chess", tmp + "/7scenes/fire/seq-01"});
  ASSERT_EQ(seven.size(), 2u);
  EXPECT_EQ(seven[0].name, "chess_seq-01");
  EXPECT_EQ(seven[1].name, "fire_seq-01");
  EXPECT_TRUE(seven[0].hasGroundTruth);
  EXPECT_FALSE(seven[1].hasGroundTruth);

  fake::makeFakeApps(tmp);
  auto loc = locations();
  loc.configDir = tmp + "/config";
  loc.outputDir = tmp + "/out";
  const auto runs = CExperimentPlan({}, loc).build(seqs);
  CExperimentPlan::writeVariantConfigs(runs);
  std::ifstream in(tmp + "/out/configs/roi_small-strict.ini");
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_NE(ss.str().find("strict_roi = true"), std::string::npos) << ss.str();
  EXPECT_NE(ss.str().find("feature = surf"), std::string::npos);
  fs::remove_all(tmp);
}
