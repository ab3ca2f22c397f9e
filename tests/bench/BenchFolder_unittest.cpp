/* roi-bench's inputs and outputs: a plan file ([Bench] ini) read strictly
 * (file:line errors, unknown keys), and an output folder reused only when it
 * is roi-bench's own. */
#include <gtest/gtest.h>
#include <roislam/bench/CBenchApp.h>
#include <roislam/testing/TestData.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "FakeApps.h"

using namespace roislam::bench;
namespace fs = std::filesystem;

namespace
{
struct Fixture
{
  std::string tmp = roislam::testing::makeTempDir("bench_folder");
  std::string seq;
  Fixture()
  {
    fake::makeFakeApps(tmp);
    seq = fake::makeFakeSequence(tmp + "/data", "textured");
  }
  ~Fixture() { fs::remove_all(tmp); }
  CBenchApp::TOptions options(const std::string& out) const
  {
    CBenchApp::TOptions o;
    o.datasets = {seq};
    o.outputDir = out;
    o.binDir = tmp;
    o.configDir = tmp + "/config";
    o.charts = false;
    o.noDefaultVariants = true;   // the plan's own runs only (Test 1's variants add some)
    o.referenceMethods = "none";  // and no cv::rgbd reference rows (their own test)
    o.selfExe = "/usr/local/bin/roi-bench";
    return o;
  }
};

std::string errorOf(const CBenchApp::TOptions& o)
{
  try
  {
    std::ostringstream out, err;
    CBenchApp(o).run(out, err);
  }
  catch (const std::exception& e)
  {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(BenchPlanFile, ReadStrictlyAndUsed)
{
  Fixture fx;
  const std::string plan = fx.tmp + "/plan.ini";
  std::ofstream(plan) << "[Bench]\ntests = 1\nfeatures = orb\n";
  auto o = fx.options(fx.tmp + "/out");
  o.planFile = plan;
  o.tests.clear();  // as roi-bench does when --plan is given without --tests
  const auto runs = CBenchApp(o).plan();
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_EQ(runs[0].id, "t1-textured-orb");
  // --tests still wins over the plan's.
  o.tests = "2";
  EXPECT_EQ(CBenchApp(o).plan().front().test, 2);

  std::ofstream(plan) << "[Bench]\ntests = 1\ntests = 2\n";
  EXPECT_EQ(errorOf(o), plan + ":3: duplicate key 'tests' (first given on line 2)");
  std::ofstream(plan) << "[Bench]\nfeaturs = orb\n";
  EXPECT_EQ(errorOf(o), "ini " + plan + ": [Bench] unknown key 'featurs' (line 2)");
  std::ofstream(plan) << "[Bench\n";
  EXPECT_EQ(errorOf(o), plan + ":1: malformed section header '[Bench'");
}

TEST(BenchOutputFolder, ReusedOnlyWhenItIsOurs)
{
  Fixture fx;
  const std::string out = fx.tmp + "/out";
  auto o = fx.options(out);
  o.tests = "1";
  o.charts = true;
  EXPECT_EQ(errorOf(o), "");
  ASSERT_TRUE(fs::exists(out + "/results.csv"));
  // Resuming is what the folder is for: the same command again works.
  std::ofstream(out + "/charts/stale.png") << "an old chart";
  EXPECT_EQ(errorOf(o), "");
  // The charts folder is replaced whole when charts are drawn (gnuplot).
  if (fs::exists(out + "/charts"))
  {
    EXPECT_FALSE(fs::exists(out + "/charts/stale.png"));
  }
  // A folder with something else in it is not used.
  std::ofstream(out + "/notes.txt") << "precious";
  const std::string e = errorOf(o);
  EXPECT_NE(e.find("output dir " + out + ": holds notes.txt"), std::string::npos) << e;
}
