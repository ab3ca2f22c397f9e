#include <gtest/gtest.h>
#include <roislam/bench/CChartWriter.h>
#include <roislam/bench/CDissertationReference.h>
#include <roislam/bench/CReportWriter.h>
#include <roislam/testing/TestData.h>

#include <filesystem>
#include <fstream>

#include "FakeApps.h"

using namespace roislam::bench;
namespace fs = std::filesystem;

namespace
{
TRunRecord rec(
    int test, const std::string& seq, const std::string& mode, const std::string& feature,
    const std::string& variant, nlohmann::json summary, bool ok = true)
{
  TRunRecord r;
  r.run.test = test;
  r.run.sequence = seq;
  r.run.mode = mode;
  r.run.feature = feature;
  r.run.variant = variant;
  r.run.maxFeatures = test == 3 ? 50 : 600;
  r.run.app = test == 1 || mode == "kf_slam" ? "roi-landmarks" : "roi-graphslam";
  r.run.id = "t" + std::to_string(test) + "-" + seq + "-" + mode + "-" + feature + "-" + variant;
  r.ok = ok;
  if (!ok)
    r.failureReason = "exit code 1: no ROI";
  r.summary = std::move(summary);
  r.wallS = 2;
  return r;
}

CDissertationReference reference()
{
  return CDissertationReference::fromFile(
      roislam::testing::sourceDir() + "/share/roi-bench/dissertation.json");
}

std::vector<TRunRecord> fakeResults()
{
  std::vector<TRunRecord> v;
  v.push_back(
      rec(1, "rgbd_dataset_freiburg1_xyz", "", "surf", "",
          {{"landmarks", 30},
           {"false_positives", 3},
           {"false_negatives", 5},
           {"precision", 0.8},
           {"recall", 0.6},
           {"fps", 4.0}}));
  v.push_back(
      rec(1, "rgbd_dataset_freiburg1_xyz", "", "surf", "hue",
          {{"landmarks", 12},
           {"false_positives", 1},
           {"false_negatives", 2},
           {"precision", 0.9},
           {"recall", 0.5},
           {"frames_with_roi", 40},
           {"frames_rejected_by_hue", 100},
           {"fps", 3.0}}));
  v.push_back(
      rec(1, "synthetic", "", "surf", "",
          {{"landmarks", 10},
           {"false_positives", nullptr},
           {"false_negatives", nullptr},
           {"precision", nullptr},
           {"recall", nullptr},
           {"fps", 6.0}}));
  for (const char* seq : {"a", "b"})
  {
    const double ate = std::string(seq) == "a" ? 0.1 : 0.2;
    v.push_back(
        rec(2, seq, "traditional", "surf", "",
            {{"ate_rmse", ate},
             {"rpe_trans_rmse", 0.01},
             {"rpe_rot_rmse_deg", 1.0},
             {"wall_s", 10.0},
             {"fps", 20.0},
             {"frontend_ms_per_frame", 40.0},
             {"edge_chi2",
              {{"median", ate * 1000}, {"with_ground_truth_noise", {{"median", ate * 100}}}}}}));
    v.push_back(
        rec(2, seq, "roi_big", "surf", "fallback",
            {{"ate_rmse", ate / 2},
             {"rpe_trans_rmse", 0.01},
             {"rpe_rot_rmse_deg", 1.0},
             {"wall_s", 15.0},
             {"fps", 10.0},
             {"frontend_ms_per_frame", 30.0}}));
  }
  v.push_back(rec(
      2, "a", "roi_big", "surf", "strict",
      {{"ate_rmse", 0.07}, {"rpe_trans_rmse", 0.01}, {"rpe_rot_rmse_deg", 1.0}, {"wall_s", 15.0}}));
  v.push_back(rec(2, "b", "roi_big", "surf", "strict", nullptr, false));
  v.push_back(
      rec(4, "a", "kf_slam", "orb", "",
          {{"kf_slam",
            {{"ate_rmse", 0.02},
             {"rpe_trans_rmse", 0.03},
             {"rpe_rot_rmse_deg", 1.5},
             {"odometry_ate_rmse", 0.025},
             {"odometry_rpe_trans_rmse", 0.035},
             {"odometry_rpe_rot_rmse_deg", 1.6}}}}));
  v.push_back(
      rec(4, "a", "graph_slam", "orb", "",
          {{"ate_rmse", 0.012}, {"rpe_trans_rmse", 0.02}, {"rpe_rot_rmse_deg", 1.2}}));
  v.push_back(rec(
      3, "a", "traditional", "surf", "",
      {{"ate_rmse", 0.3}, {"rpe_trans_rmse", 0.05}, {"rpe_rot_rmse_deg", 4.0}, {"wall_s", 5.0}}));
  return v;
}
}  // namespace

TEST(CReportWriter, meanStd)
{
  const auto ms = meanStd({0.1, 0.2});
  ASSERT_TRUE(ms);
  EXPECT_NEAR(ms->mean, 0.15, 1e-12);
  EXPECT_NEAR(ms->std, 0.0707107, 1e-6);  // sample std
  EXPECT_FALSE(meanStd({}));
}

TEST(CReportWriter, tablesHaveOurAndDissertationCells)
{
  const std::string md = CReportWriter({}, reference()).render(fakeResults());
  // Test 1: a TUM name maps to the dissertation's sequence 1.
  EXPECT_NE(md.find("| rgbd_dataset_freiburg1_xyz | 30 / 3 / 5 | 33 / 2 / 10 |"), std::string::npos)
      << md;
  EXPECT_NE(md.find("| synthetic | 10 / n/a / n/a | — |"), std::string::npos) << md;
  EXPECT_NE(md.find("1 (fr1/xyz)"), std::string::npos);
  // Precision / recall per extractor next to the dissertation's rates and fps.
  EXPECT_NE(
      md.find("| SURF | 0.800 (n=1) | 0.600 (n=1) | 80.3 % | 77.7 % | 5.00 ± 1.41 (n=2) | 0.67 |"),
      std::string::npos)
      << md;
  // Test 2 ATE: mean ± std and the dissertation's value; failures counted.
  EXPECT_NE(md.find("| traditional | 0.1500 ± 0.0707 (n=2) | 0.143 ± 0.123 |"), std::string::npos)
      << md;
  EXPECT_NE(
      md.find("| big ROI — strict (dissertation's behaviour) | 0.0700 (n=1, 1 failed) | 0.078 ± "
              "0.042 |"),
      std::string::npos)
      << md;
  EXPECT_NE(
      md.find("| big ROI + fallback (**ours**) | 0.0750 ± 0.0354 (n=2) |"), std::string::npos);
  // Per-sequence table shows the failure.
  EXPECT_NE(md.find("FAILED (exit code 1: no ROI)"), std::string::npos);
  // The edges' chi² per sequence: median / with the ground truth's noise; a
  // run without it reads a dash, a failed one FAILED.
  EXPECT_NE(md.find("are the graph's edges honest?"), std::string::npos) << md;
  EXPECT_NE(md.find("| a | traditional | 100.0 / 10.0 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| b | traditional | 200.0 / 20.0 |"), std::string::npos) << md;
  EXPECT_NE(
      md.find("| b | big ROI — strict (dissertation's behaviour) | FAILED |"), std::string::npos)
      << md;
  // Test 3 row with the dissertation's 50-feature figures.
  EXPECT_NE(
      md.find("| traditional | 0.3000 (n=1) | 0.470 ± 0.363 | 0.0500 (n=1) | 0.074 | 4.000 (n=1) | "
              "5.91 | 5.0 (n=1) | 3.18 |"),
      std::string::npos)
      << md;
  // Speed: ROI/traditional wall-time and front-end ratios over sequences
  // where both succeeded.
  EXPECT_NE(
      md.find("| big ROI + fallback (**ours**) | SURF | 10.00 ± 0.00 (n=2) | 1.50 | 30.0 ± 0.0 "
              "(n=2) | 0.75 |"),
      std::string::npos)
      << md;
  EXPECT_NE(md.find("- `t2-b-roi_big-surf-strict`: exit code 1: no ROI"), std::string::npos);
  // Test 1's hue variant: its own rows (no dissertation value), side by side.
  EXPECT_NE(md.find("| rgbd_dataset_freiburg1_xyz (hue) | 12 / 1 / 2 | — |"), std::string::npos)
      << md;
  EXPECT_NE(
      md.find("| SURF (hue) | 0.900 (n=1) | 0.500 (n=1) | — | — | 3.00 (n=1) | — |"),
      std::string::npos)
      << md;
  EXPECT_NE(
      md.find("| rgbd_dataset_freiburg1_xyz | SURF | 30 → 12 | 0.800 → 0.900 | 0.600 → 0.500 | "
              "n/a → 40 |"),
      std::string::npos)
      << md;
  EXPECT_NE(
      md.find("| rgbd_dataset_freiburg1_xyz (hue) | SURF | ok | 40 | 100 |"), std::string::npos)
      << md;
  // Test 4: EKF, odometry (from the EKF run) and graph SLAM side by side.
  EXPECT_NE(
      md.find("| a | ORB | 0.0200 | 0.0250 | 0.0120 | 0.0300 / 1.50 | 0.0350 / 1.60 | "
              "0.0200 / 1.20 |"),
      std::string::npos)
      << md;
}

namespace
{
/** A paired cost entry for sequence `seq`, SURF: traditional and big ROI. */
TPairedCost pairedEntry(const std::string& seq, double roiFrontMs)
{
  TPairedCost c;
  c.sequence = seq;
  c.sequencePath = "/data/" + seq;
  c.feature = "surf";
  c.maxFeatures = 600;
  c.passes = 1;
  TPairedCost::TVersion t;
  t.key = "traditional";
  t.frames = 10;
  t.wallMsPerFrame = 50;
  t.cpuMsPerFrame = 80;
  t.frontEndMsPerFrame = 40;
  t.fps = 20;
  t.ateRmse = 0.01;
  TPairedCost::TVersion b = t;
  b.key = "roi_big/fallback";
  b.wallMsPerFrame = 40;
  b.cpuMsPerFrame = 60;
  b.frontEndMsPerFrame = roiFrontMs;
  b.fps = 25;
  b.wallRatio = 0.8;
  b.cpuRatio = 0.75;
  b.frontEndRatio = roiFrontMs / 40;
  c.versions = {t, b};
  return c;
}
}  // namespace

TEST(CReportWriter, speedTableFromThePairedFile)
{
  const std::string tmp = roislam::testing::makeTempDir("bench_paired");
  auto a = pairedEntry("a", 20);
  auto b = pairedEntry("b", 30);
  b.leftOut.emplace_back("roi_big/strict", "its Test-2 run failed: exit code 1: no ROI");
  TPairedCost failed;
  failed.sequence = "b";
  failed.feature = "orb";
  failed.passes = 1;
  failed.error = "roi_big: boom";
  savePairedCosts({a, b, failed}, tmp + "/speed.json");
  // Round trip.
  const auto loaded = loadPairedCosts(tmp + "/speed.json");
  ASSERT_EQ(loaded.size(), 3u);
  EXPECT_EQ(loaded[1].toJson(), b.toJson());
  EXPECT_FALSE(loaded[2].ok());

  CReportWriter::TOptions o;
  o.pairedCostFile = tmp + "/speed.json";
  const std::string md = CReportWriter(o, reference()).render(fakeResults());
  EXPECT_NE(md.find("## Speed (Test 2 versions, paired measurement)"), std::string::npos) << md;
  EXPECT_NE(md.find("Figures from `speed.json`"), std::string::npos);
  // Front end mean over the sequences, ratio of the sums (50 / 80), fps,
  // wall and CPU cost ratios, peak RSS from the Test-2 runs (none: n/a).
  EXPECT_NE(
      md.find("| big ROI + fallback (**ours**) | SURF | 25.0 ± 7.1 (n=2) | 0.62 | 25.00 ± 0.00 "
              "(n=2) | 0.80 | 0.75 | n/a |"),
      std::string::npos)
      << md;
  EXPECT_NE(
      md.find("| traditional | SURF | 40.0 ± 0.0 (n=2) | 1.00 | 20.00 ± 0.00 (n=2) | 1.00 | 1.00 "
              "| n/a |"),
      std::string::npos)
      << md;
  EXPECT_NE(
      md.find("- b, SURF: roi_big/strict left out (its Test-2 run failed: exit code 1: no ROI)"),
      std::string::npos)
      << md;
  EXPECT_NE(md.find("- b, ORB: paired measurement FAILED: roi_big: boom"), std::string::npos) << md;
  // The single runs' table is not rendered.
  EXPECT_EQ(md.find("wall time ratio vs traditional"), std::string::npos);

  // Missing or malformed file: a one-line error naming it.
  for (const std::string& text :
       {std::string(), std::string("{\"runs\": 3"),
        std::string("{\"format\": \"other\", \"runs\": []}"),
        std::string("{\"format\": \"roi-bench paired cost 1\", "
                    "\"runs\": [{\"sequence\": \"a\"}]}")})
  {
    const std::string file = tmp + (text.empty() ? "/missing.json" : "/bad.json");
    if (!text.empty())
      std::ofstream(file) << text;
    o.pairedCostFile = file;
    try
    {
      CReportWriter(o, reference());
      ADD_FAILURE() << "no error for " << text;
    }
    catch (const std::runtime_error& e)
    {
      const std::string m = e.what();
      EXPECT_EQ(m.rfind(file + ": ", 0), 0u) << m;
      EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    }
  }
  fs::remove_all(tmp);
}

TEST(CDissertationReference, lookups)
{
  const auto ref = reference();
  EXPECT_EQ(ref.sequenceId("rgbd_dataset_freiburg3_nostructure_notexture_far"), 8);
  EXPECT_EQ(ref.sequenceId("freiburg1_360"), 6);
  EXPECT_FALSE(ref.sequenceId("rgbd_dataset_freiburg1_rpy_first250"));
  const auto t = ref.test1(7, "orb");
  ASSERT_TRUE(t);
  EXPECT_EQ((*t)[0], 236);
  EXPECT_NEAR(ref.scalar(2, "roi_big", "orb", "duration_min").value(), 40.4, 1e-9);
  EXPECT_FALSE(ref.scalar(2, "roi_big", "orb", "rpe_trans"));
  EXPECT_NEAR(ref.ate(3, "roi_big", "surf")->first, 0.402, 1e-9);
  EXPECT_FALSE(ref.ate(3, "roi_big", "orb"));
  EXPECT_THROW(CDissertationReference::fromFile("/nonexistent.json"), std::runtime_error);
}

TEST(CChartWriter, drawsPngs)
{
  CChartWriter charts;
  if (!charts.available())
    GTEST_SKIP() << "gnuplot not installed";
  const std::string tmp = roislam::testing::makeTempDir("bench_charts");
  auto records = fakeResults();
  // Trajectory plot: ground truth and an estimate equal to it.
  const std::string seq = fake::makeFakeSequence(tmp, "a");
  for (auto& r : records)
    if (r.run.test == 2 && r.run.sequence == "a")
    {
      r.run.sequencePath = seq;
      r.run.appOutputDir = tmp + "/" + r.run.id;
      fs::create_directories(r.run.appOutputDir);
      fs::copy_file(seq + "/groundtruth.txt", r.run.appOutputDir + "/trajectory.txt");
    }
  const auto pngs = charts.write(records, tmp + "/charts");
  for (const char* name :
       {"test1_landmarks.png", "test1_false_positives.png", "test2_ate.png", "test2_rpe_trans.png",
        "test2_rpe_rot.png", "test2_duration.png", "test3_ate.png", "traj_a_surf.png",
        "test4_ate.png"})
  {
    EXPECT_NE(std::find(pngs.begin(), pngs.end(), name), pngs.end()) << name;
    const fs::path p = fs::path(tmp) / "charts" / name;
    ASSERT_TRUE(fs::exists(p)) << p;
    EXPECT_GT(fs::file_size(p), 1000u) << p;
  }
  fs::remove_all(tmp);
}
