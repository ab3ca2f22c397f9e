// roi-bench on the real apps (synthetic textured sequence): the figures it
// reports must equal those of the same app run by hand, and the paired speed
// stage measures every Test-2 version over the whole sequence.
#include <gtest/gtest.h>
#include <roislam/bench/CBenchApp.h>
#include <roislam/bench/CResultsCollector.h>
#include <roislam/bench/ProcessUtils.h>
#include <roislam/bench/TPairedCost.h>
#include <roislam/testing/TestData.h>

#include <filesystem>
#include <sstream>

using namespace roislam::bench;
namespace fs = std::filesystem;

TEST(EndToEnd, figuresEqualHandRuns)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "textured");
  const std::string bin = roislam::testing::binaryDir() + "/apps";
  for (const char* app : {"roi-landmarks", "roi-graphslam", "cv-odometry"})
    if (!fs::exists(bin + "/" + app + "/" + app))
      GTEST_SKIP() << app << " not built";
  const std::string tmp = roislam::testing::makeTempDir("bench_e2e");
  CBenchApp::TOptions o;
  o.datasets = {seq};
  o.outputDir = tmp + "/out";
  o.binDir = bin;
  o.configDir = roislam::testing::sourceDir() + "/config";
  o.tests = "1,2";
  o.plan.features = {"surf"};
  o.plan.modes = {"traditional", "roi_big"};
  o.noDefaultVariants = true;
  o.referenceMethods = "rgbdicp";
  std::ostringstream out, err;
  ASSERT_EQ(CBenchApp(o).run(out, err), 0) << err.str();
  const auto records = CResultsCollector::loadFolder(o.outputDir);
  ASSERT_EQ(records.size(), 4u);  // Test 1, Test 2 (two versions) and the reference row
  EXPECT_TRUE(fs::exists(o.outputDir + "/report.md"));
  EXPECT_TRUE(fs::exists(o.outputDir + "/results.csv"));

  // The paired speed stage: both versions, every frame, in the report.
  const auto costs = loadPairedCosts(o.outputDir + "/speed.json");
  ASSERT_EQ(costs.size(), 1u);
  ASSERT_TRUE(costs[0].ok()) << costs[0].error;
  ASSERT_EQ(costs[0].versions.size(), 2u);
  EXPECT_EQ(costs[0].versions[0].key, "traditional");
  EXPECT_EQ(costs[0].versions[1].key, "roi_big");
  for (const auto& r : records)
    if (r.run.test == 2 && r.run.mode == "traditional")
    {
      ASSERT_TRUE(r.number("frames"));
      EXPECT_EQ(costs[0].versions[1].frames, static_cast<std::size_t>(*r.number("frames")));
      // The same run, so the same trajectory error as the app's.
      ASSERT_TRUE(costs[0].versions[0].ateRmse);
      EXPECT_NEAR(*costs[0].versions[0].ateRmse, *r.number("ate_rmse"), 1e-9);
    }
  const std::string md = readFile(o.outputDir + "/report.md");
  EXPECT_NE(md.find("## Speed (Test 2 versions, paired measurement)"), std::string::npos) << md;
  EXPECT_NE(md.find("| big ROI | SURF | "), std::string::npos) << md;

  for (const auto& r : records)
  {
    // Run the exact recorded command again by hand, into another folder.
    auto argv = r.run.argv;
    const std::string handOut = tmp + "/hand_" + r.run.id;
    for (std::size_t i = 0; i + 1 < argv.size(); ++i)
      if (argv[i] == "--output-dir")
        argv[i + 1] = handOut;
    const auto p = runProcess(argv, "", tmp + "/hand.log");
    const bool handOk = p.succeeded() && fs::exists(handOut + "/summary.json");
    EXPECT_EQ(handOk, r.ok) << r.run.id << ": " << r.failureReason;
    if (!handOk || !r.ok)
      continue;
    const auto hand = nlohmann::json::parse(readFile(handOut + "/summary.json"));
    for (const char* key :
         {"frames", "landmarks", "false_positives", "false_negatives", "precision", "recall",
          "keyframes", "ate_rmse", "rpe_trans_rmse", "failed_frames"})
    {
      if (hand.contains(key))
      {
        EXPECT_EQ(hand.at(key), r.summary.at(key)) << r.run.id << " " << key;
      }
    }
  }
  fs::remove_all(tmp);
}
