// roi-eval end to end: files in, table / JSON / aligned trajectory / PNG out,
// one-line errors with a non-zero exit code on bad input.
#include <gtest/gtest.h>
#include <mrpt/poses/CPose3DQuat.h>
#include <roislam/io/TumTrajectory.h>
#include <roislam/testing/TestData.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

namespace
{
namespace fs = std::filesystem;

struct TRun
{
  int code = -1;
  std::string out, err;
};

TRun run(const std::string& args, const std::string& dir)
{
  const std::string exe = roislam::testing::binaryDir() + "/apps/roi-eval/roi-eval";
  const std::string errFile = dir + "/stderr.txt";
  const std::string cmd = "'" + exe + "' " + args + " 2> '" + errFile + "'";
  TRun r;
  FILE* p = ::popen(cmd.c_str(), "r");
  if (!p)
    return r;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), buf.size(), p))
    r.out += buf.data();
  const int status = ::pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream e(errFile);
  r.err.assign(std::istreambuf_iterator<char>(e), {});
  return r;
}

/** Ground truth at 100 Hz and an estimate at 30 Hz, rigidly moved, with a
 *  known 0.01 m offset along x on every other pose. */
void writeInputs(const std::string& dir)
{
  std::ofstream gt(dir + "/gt.txt"), est(dir + "/est.txt");
  gt << "# timestamp tx ty tz qx qy qz qw\n";
  gt.precision(17);
  est.precision(17);
  const mrpt::poses::CPose3D T(1, 2, 3, 0.5, 0.2, -0.1);
  for (int k = 0; k < 1000; ++k)
  {
    const double s = k * 0.01;
    const mrpt::poses::CPose3D g(std::sin(s), std::cos(0.7 * s), 0.2 * s, 0.3 * s, 0, 0);
    const mrpt::poses::CPose3DQuat gq(g);
    gt << 100 + s << ' ' << g.x() << ' ' << g.y() << ' ' << g.z() << ' ' << gq.quat().x() << ' '
       << gq.quat().y() << ' ' << gq.quat().z() << ' ' << gq.quat().r() << '\n';
    if (k % 3 == 0)
    {
      mrpt::poses::CPose3D e = g;
      e.x_incr((k / 3) % 2 ? 0.01 : -0.01);
      const mrpt::poses::CPose3D te = T + e;
      const mrpt::poses::CPose3DQuat eq(te);
      est << 100 + s << ", " << te.x() << ", " << te.y() << ", " << te.z() << ", " << eq.quat().x()
          << ", " << eq.quat().y() << ", " << eq.quat().z() << ", " << eq.quat().r() << '\n';
    }
  }
}
}  // namespace

TEST(RoiEvalApp, JsonTableAlignedAndPlot)
{
  const auto dir = roislam::testing::makeTempDir("eval_app");
  writeInputs(dir);
  const std::string io = "--gt '" + dir + "/gt.txt' --est '" + dir + "/est.txt'";

  const TRun j = run(io + " --json --save-aligned '" + dir + "/aligned.txt'", dir);
  ASSERT_EQ(j.code, 0) << j.err;
  const auto doc = nlohmann::json::parse(j.out);
  EXPECT_EQ(doc["ate"]["pairs"].get<int>(), 334);
  // Offsets of +-1 cm along the body x axis alternate, nearly an RMS of 1 cm
  // (the alignment absorbs a tiny part of them).
  EXPECT_NEAR(doc["ate"]["rmse"].get<double>(), 0.01, 2e-4);
  EXPECT_GT(doc["rpe"]["pairs"].get<int>(), 290);
  EXPECT_TRUE(doc["rpe"].contains("rot_rmse_deg"));

  // The aligned estimate is in the ground-truth frame: within ~1 cm of it.
  const auto aligned = roislam::io::loadTumTrajectory(dir + "/aligned.txt");
  const auto gt = roislam::io::loadTumTrajectory(dir + "/gt.txt");
  ASSERT_EQ(aligned.size(), 334u);
  EXPECT_LT((aligned[10].pose.translation() - gt[30].pose.translation()).norm(), 0.011);

  const TRun t = run(io + " --delta 10 --delta-unit f", dir);
  ASSERT_EQ(t.code, 0) << t.err;
  EXPECT_NE(t.out.find("ATE  334 pairs"), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("RPE  "), std::string::npos) << t.out;

  if (std::system("gnuplot --version > /dev/null 2>&1") == 0)
  {
    const TRun p =
        run(io + " --plot '" + dir + "/plot.png' --plot-errors '" + dir + "/errors.png'", dir);
    ASSERT_EQ(p.code, 0) << p.err;
    EXPECT_GT(fs::file_size(dir + "/plot.png"), 10000u);
    EXPECT_GT(fs::file_size(dir + "/errors.png"), 10000u);
  }
  fs::remove_all(dir);
}

TEST(RoiEvalApp, BadInputGivesOneLineErrorAndExitCode1)
{
  const auto dir = roislam::testing::makeTempDir("eval_app_bad");
  writeInputs(dir);
  const std::string gt = "--gt '" + dir + "/gt.txt'";
  {
    std::ofstream(dir + "/bad.txt") << "# x\n1 2 3 4 0 0 0 1\n1.5 2 3 0 0 0 1\n";
    const TRun r = run(gt + " --est '" + dir + "/bad.txt'", dir);
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(
        r.err, "roi-eval: error: " + dir +
                   "/bad.txt:3: expected 8 values (timestamp tx ty tz qx qy qz qw), found 7\n");
    EXPECT_TRUE(r.out.empty());
  }
  {
    const TRun r = run(gt + " --est '" + dir + "/none.txt'", dir);
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(r.err, "roi-eval: error: " + dir + "/none.txt: cannot open\n");
  }
  {
    std::ofstream(dir + "/far.txt") << "5 1 2 3 0 0 0 1\n6 1 2 3 0 0 0 1\n7 1 2 3 0 0 0 1\n";
    const TRun r = run(gt + " --est '" + dir + "/far.txt'", dir);
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("far.txt vs "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("no estimated stamp has a ground-truth stamp"), std::string::npos);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1);
  }
  {
    std::ofstream(dir + "/two.txt") << "100 1 2 3 0 0 0 1\n100.5 1 2 3 0 0 0 1\n";
    const TRun r = run(gt + " --est '" + dir + "/two.txt'", dir);
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("only 2 estimated stamps associate"), std::string::npos) << r.err;
  }
  {
    const TRun r = run(gt + " --est '" + dir + "/est.txt' --max-difference 0", dir);
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("max_difference: must be > 0"), std::string::npos) << r.err;
  }
  {
    // A graph whose nodes' frames lie outside the ground truth (100-110 s).
    std::string inf;
    for (int k = 0; k < 21; ++k)
      inf += (k == 0 || k == 6 || k == 11 || k == 15 || k == 18 || k == 20) ? " 1" : " 0";
    std::ofstream(dir + "/g.graph") << "VERTEX3 0 0 0 0 0 0 0\nVERTEX3 1 1 0 0 0 0 0\n"
                                    << "EDGE3 0 1 1 0 0 0 0 0" << inf << "\n";
    std::ofstream(dir + "/frames.csv") << "index,timestamp,keyframe\n0,5.0,0\n1,6.0,1\n";
    const std::string graph = " --graph '" + dir + "/g.graph' --frames '" + dir + "/frames.csv'";
    TRun r = run(gt + " --est '" + dir + "/est.txt'" + graph, dir);
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("g.graph: no edge could be checked"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    std::ofstream(dir + "/frames.csv") << "index,timestamp\n0,5.0\n";
    r = run(gt + " --est '" + dir + "/est.txt'" + graph, dir);
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("frames.csv:1: no 'keyframe' column"), std::string::npos) << r.err;
  }
  {
    // Unwritable output: error, no partial file.
    const TRun r =
        run(gt + " --est '" + dir + "/est.txt' --save-aligned '" + dir + "/no/such/a.txt'", dir);
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("/no/such/a.txt"), std::string::npos) << r.err;
  }
  fs::remove_all(dir);
}
