#include <gtest/gtest.h>
#include <roislam/bench/CBenchApp.h>
#include <roislam/bench/CBenchRunner.h>
#include <roislam/bench/CProgressBar.h>
#include <roislam/bench/CResultsCollector.h>
#include <roislam/bench/ProcessUtils.h>
#include <roislam/bench/TPairedCost.h>
#include <roislam/testing/TestData.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "FakeApps.h"

using namespace roislam::bench;
namespace fs = std::filesystem;

namespace
{
int countLines(const std::string& file)
{
  std::ifstream in(file);
  int n = 0;
  std::string l;
  while (std::getline(in, l))
    ++n;
  return n;
}

struct Fixture
{
  std::string tmp = roislam::testing::makeTempDir("bench_runner");
  std::string textured, featureless;
  Fixture()
  {
    fake::makeFakeApps(tmp);
    textured = fake::makeFakeSequence(tmp + "/data", "textured");
    featureless = fake::makeFakeSequence(tmp + "/data", "featureless");
  }
  ~Fixture() { fs::remove_all(tmp); }
  CBenchApp::TOptions appOptions(const std::string& out) const
  {
    CBenchApp::TOptions o;
    o.datasets = {textured, featureless};
    o.outputDir = out;
    o.binDir = tmp;
    o.configDir = tmp + "/config";
    o.charts = false;
    o.selfExe = "/usr/local/bin/roi-bench";
    o.referenceMethods = "none";  // the reference rows have their own test
    o.speedPasses = 0;            // the paired speed stage has its own test
    return o;
  }
};
}  // namespace

TEST(ProcessUtils, quotingAndExitStatus)
{
  EXPECT_EQ(shellQuote("abc/d-e.f"), "abc/d-e.f");
  EXPECT_EQ(shellQuote("a b"), "'a b'");
  EXPECT_EQ(shellQuote("it's"), "'it'\\''s'");
  EXPECT_EQ(shellQuote(""), "''");
  EXPECT_EQ(shellJoin({"x", "a b"}), "x 'a b'");

  const auto ok = runProcess({"sh", "-c", "exit 3"}, "", "");
  EXPECT_TRUE(ok.started);
  EXPECT_EQ(ok.exitCode, 3);
  EXPECT_FALSE(ok.succeeded());
  const auto missing = runProcess({"/nonexistent/prog"}, "", "");
  EXPECT_FALSE(missing.started);
  const auto slow = runProcess({"sleep", "5"}, "", "", 0.3);
  EXPECT_TRUE(slow.timedOut);
  EXPECT_LT(slow.wallS, 3.0);
}

TEST(CBenchRunner, runsResumesAndRecordsFailures)
{
  Fixture fx;
  const std::string out = fx.tmp + "/out";
  auto o = fx.appOptions(out);
  o.tests = "2";
  o.jobs = 2;
  std::ostringstream sout, serr;
  ASSERT_EQ(CBenchApp(o).run(sout, serr), 0);
  // 2 sequences x 3 features x (1 + 2 modes x 5 variants) versions.
  EXPECT_EQ(countLines(fx.tmp + "/calls.log"), 66);
  EXPECT_NE(serr.str().find("66/66"), std::string::npos) << serr.str();

  const auto records = CResultsCollector::loadFolder(out);
  ASSERT_EQ(records.size(), 66u);
  int failed = 0;
  for (const auto& r : records)
  {
    const bool shouldFail = r.run.sequence == "featureless" && r.run.variant == "strict";
    EXPECT_EQ(r.ok, !shouldFail) << r.run.id;
    if (!r.ok)
    {
      ++failed;
      EXPECT_NE(
          r.failureReason.find("exit code 1: roi-graphslam: error: no ROI"), std::string::npos)
          << r.failureReason;
      EXPECT_EQ(r.exitCode, 1);
    }
    else
    {
      EXPECT_GT(r.wallS, 0);
      EXPECT_TRUE(fs::exists(fs::path(r.run.runDir) / "command.sh"));
    }
  }
  EXPECT_EQ(failed, 6);

  // Second invocation: everything is complete, nothing runs again.
  std::ostringstream s2, e2;
  ASSERT_EQ(CBenchApp(o).run(s2, e2), 0);
  EXPECT_EQ(countLines(fx.tmp + "/calls.log"), 66);
  EXPECT_NE(e2.str().find("66 already done"), std::string::npos) << e2.str();

  // Deleting one marker reruns exactly that run; --retry-failed reruns the failures.
  fs::remove(fs::path(out) / "runs" / "t2-textured-roi_big-orb-600-fallback" / "run.json");
  std::ostringstream s3, e3;
  CBenchApp(o).run(s3, e3);
  EXPECT_EQ(countLines(fx.tmp + "/calls.log"), 67);
  o.retryFailed = true;
  CBenchApp(o).run(s3, e3);
  EXPECT_EQ(countLines(fx.tmp + "/calls.log"), 73);

  // results.csv: one row per run plus the header, with the exact command.
  const std::string csv = readFile(out + "/results.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 67);
  EXPECT_NE(
      csv.find(",failed,exit code 1: roi-graphslam: error: no ROI in frame 0,"), std::string::npos);
  EXPECT_TRUE(fs::exists(out + "/report.md"));
}

// The paired speed stage on the fake apps: it cannot measure (the fake
// configs are no SLAM configs), which must be a recorded, reported failure
// naming the config, with the strict ROI versions that failed left out.
TEST(CBenchApp, pairedSpeedStageRecordsWhatItCouldNotMeasure)
{
  Fixture fx;
  const std::string out = fx.tmp + "/out";
  auto o = fx.appOptions(out);
  o.tests = "2";
  o.plan.features = {"orb"};
  o.speedPasses = 1;
  std::ostringstream sout, serr;
  ASSERT_EQ(CBenchApp(o).run(sout, serr), 0) << serr.str();
  const auto costs = loadPairedCosts(out + "/speed.json");
  ASSERT_EQ(costs.size(), 2u);  // per sequence x extractor
  for (const auto& c : costs)
  {
    EXPECT_EQ(c.feature, "orb");
    EXPECT_EQ(c.passes, 1);
    EXPECT_FALSE(c.ok());
    EXPECT_NE(c.error.find(fx.tmp + "/config/"), std::string::npos) << c.error;
    // Traditional first, then the ROI versions whose Test-2 run succeeded.
    ASSERT_FALSE(c.versions.empty());
    EXPECT_EQ(c.versions.front().key, "traditional");
    const std::size_t left = c.sequence == "featureless" ? 2 : 0;
    EXPECT_EQ(c.leftOut.size(), left) << c.sequence;
    EXPECT_EQ(c.versions.size(), 11 - left) << c.sequence;
    for (const auto& [key, why] : c.leftOut)
    {
      EXPECT_NE(key.find("/strict"), std::string::npos) << key;
      EXPECT_NE(why.find("no ROI"), std::string::npos) << why;
    }
  }
  EXPECT_NE(serr.str().find("warning: paired speed measurement textured, orb"), std::string::npos)
      << serr.str();
  const std::string md = readFile(out + "/report.md");
  EXPECT_NE(md.find("- featureless, ORB: paired measurement FAILED: "), std::string::npos) << md;
  EXPECT_NE(md.find("- featureless, ORB: roi_big/strict left out"), std::string::npos) << md;

  // Resumed: the failed measurements are kept, unless --retry-failed.
  std::ostringstream s2, e2;
  ASSERT_EQ(CBenchApp(o).run(s2, e2), 0);
  EXPECT_EQ(e2.str().find("paired speed measurement"), std::string::npos) << e2.str();
  o.retryFailed = true;
  std::ostringstream s3, e3;
  ASSERT_EQ(CBenchApp(o).run(s3, e3), 0);
  EXPECT_NE(e3.str().find("paired speed measurement"), std::string::npos) << e3.str();

  // --speed-passes 0: no speed stage, and a malformed speed.json is the
  // report's one-line error naming it.
  o.retryFailed = false;
  o.speedPasses = 0;
  writeFileAtomically(out + "/speed.json", "{not json");
  std::ostringstream s4, e4;
  try
  {
    CBenchApp(o).run(s4, e4);
    ADD_FAILURE() << "no error for a malformed speed.json";
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_EQ(std::string(e.what()).rfind(out + "/speed.json: ", 0), 0u) << e.what();
  }
  EXPECT_THROW(
      {
        auto bad = o;
        bad.speedPasses = -1;
        CBenchApp app(bad);
      },
      std::invalid_argument);
}

TEST(CBenchApp, referenceRowsInReportAndCsv)
{
  Fixture fx;
  const std::string out = fx.tmp + "/out";
  auto o = fx.appOptions(out);
  o.tests = "2";
  o.plan.features = {"orb"};
  o.plan.modes = {"traditional"};
  o.referenceMethods = "rgbd,rgbdicp";
  std::ostringstream sout, serr;
  ASSERT_EQ(CBenchApp(o).run(sout, serr), 0);
  const auto records = CResultsCollector::loadFolder(out);
  // 2 sequences x (traditional ORB + 2 reference methods).
  ASSERT_EQ(records.size(), 6u);
  std::size_t refs = 0;
  for (const auto& r : records)
    if (r.run.test == 0)
    {
      ++refs;
      EXPECT_TRUE(r.ok) << r.run.id << ": " << r.failureReason;
      EXPECT_EQ(r.run.app, "cv-odometry");
    }
  EXPECT_EQ(refs, 4u);
  const std::string report = readFile(out + "/report.md");
  EXPECT_NE(report.find("## Reference: OpenCV's cv::rgbd odometry"), std::string::npos) << report;
  EXPECT_NE(
      report.find("| textured | cv::rgbd rgbdicp (cv::rgbd::Fakergbdicp) | 0.0030 | 0.0030 | "
                  "0.300 | 3.5 | 0 |"),
      std::string::npos)
      << report;
  // Ours beside it: the fake traditional ORB run's ATE 0.013 m, 1.5 s over 10 frames.
  EXPECT_NE(
      report.find("| textured | ours, best: test 2 traditional ORB | 0.0130 | 0.0030 | 0.100 | "
                  "150.0 |"),
      std::string::npos)
      << report;
  const std::string csv = readFile(out + "/results.csv");
  EXPECT_NE(csv.find(",ms_per_frame,"), std::string::npos);
  EXPECT_NE(csv.find("ref-textured-cv_rgbd,0,textured,cv-odometry,cv_rgbd,"), std::string::npos)
      << csv;
}

TEST(CBenchRunner, summarySaysFailedAndMissingSummary)
{
  Fixture fx;
  const std::string exe = fx.tmp + "/failing";
  fake::writeExecutable(
      exe,
      "#!/bin/sh\nmkdir -p \"$2\"\necho '{\"failed\": true, \"error\": \"lost\"}' > "
      "\"$2/summary.json\"\n");
  const std::string silent = fx.tmp + "/silent";
  fake::writeExecutable(silent, "#!/bin/sh\nexit 0\n");
  TBenchRun a;
  a.id = "a";
  a.runDir = fx.tmp + "/runs/a";
  a.appOutputDir = a.runDir + "/output";
  a.argv = {exe, "--output-dir", a.appOutputDir};
  TBenchRun b = a;
  b.id = "b";
  b.runDir = fx.tmp + "/runs/b";
  b.appOutputDir = b.runDir + "/output";
  b.argv = {silent};
  const auto recs = CBenchRunner().run({a, b});
  ASSERT_EQ(recs.size(), 2u);
  EXPECT_FALSE(recs[0].ok);
  EXPECT_EQ(recs[0].failureReason, "summary says failed: lost");
  EXPECT_FALSE(recs[1].ok);
  EXPECT_EQ(recs[1].failureReason, "no summary.json written");
  EXPECT_TRUE(CBenchRunner::loadCompleted(b.runDir).has_value());
}

TEST(CBenchApp, emitJobsAndMerge)
{
  Fixture fx;
  auto o = fx.appOptions(fx.tmp + "/shared_out");
  o.tests = "1";
  o.emitJobs = true;
  std::ostringstream sout, serr;
  ASSERT_EQ(CBenchApp(o).run(sout, serr), 0);
  std::vector<std::string> lines;
  {
    std::stringstream ss(sout.str());
    std::string l;
    while (std::getline(ss, l))
      lines.push_back(l);
  }
  ASSERT_EQ(lines.size(), 12u);  // 2 sequences x 3 features x (plain + hue)
  EXPECT_EQ(
      lines[0], "/usr/local/bin/roi-bench --datasets " + fx.textured + " " + fx.featureless +
                    " --output-dir " + fx.tmp + "/shared_out --tests 1 --jobs 1 --no-report " +
                    "--bin-dir " + fx.tmp + " --config-dir " + fx.tmp +
                    "/config --reference-methods none --only t1-textured-surf");
  EXPECT_EQ(countLines(fx.tmp + "/calls.log"), 0) << "--emit-jobs must not run anything";

  // Two "machines" each run half of the jobs into their own folder, then merge.
  auto m1 = fx.appOptions(fx.tmp + "/m1");
  m1.tests = "1";
  m1.only = {"t1-textured-surf", "t1-textured-sift", "t1-textured-orb"};
  m1.noReport = true;
  auto m2 = m1;
  m2.outputDir = fx.tmp + "/m2";
  m2.only = {"t1-featureless-surf", "t1-featureless-sift", "t1-featureless-orb"};
  CBenchApp(m1).run(sout, serr);
  CBenchApp(m2).run(sout, serr);
  EXPECT_FALSE(fs::exists(fx.tmp + "/m1/report.md"));
  EXPECT_EQ(countLines(fx.tmp + "/calls.log"), 6);

  auto mg = fx.appOptions(fx.tmp + "/merged");
  mg.tests = "1";
  mg.merge = true;
  mg.mergeDirs = {fx.tmp + "/m1", fx.tmp + "/m2"};
  ASSERT_EQ(CBenchApp(mg).run(sout, serr), 0);
  const auto recs = CResultsCollector::loadFolder(fx.tmp + "/merged");
  ASSERT_EQ(recs.size(), 6u);
  for (const auto& r : recs)
  {
    EXPECT_TRUE(r.ok);
    EXPECT_EQ(r.run.runDir.rfind(fx.tmp + "/merged/runs/", 0), 0u) << r.run.runDir;
  }
  const std::string report = readFile(fx.tmp + "/merged/report.md");
  EXPECT_NE(report.find("| textured | 10 / 1 / 2 |"), std::string::npos) << report;
  EXPECT_NE(report.find("| featureless | 10 / 1 / 2 |"), std::string::npos);
  EXPECT_THROW(CResultsCollector::merge({fx.tmp + "/data"}, fx.tmp + "/x"), std::runtime_error);
}

TEST(CProgressBar, format)
{
  CBenchRunner::TProgress p;
  p.total = 10;
  p.done = 5;
  p.failed = 1;
  p.elapsedS = 65;
  p.etaS = 3725;
  p.lastId = "t1-x-surf";
  std::ostringstream os;
  CProgressBar bar(os, 10);
  EXPECT_EQ(
      bar.format(p),
      "[#####.....] 5/10 (1 failed, 0 already done) 01:05 elapsed, ETA 1:02:05  t1-x-surf");
}
