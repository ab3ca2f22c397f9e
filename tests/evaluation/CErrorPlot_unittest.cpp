// CErrorPlot: the errors-over-time PNG through gnuplot; clear errors.
#include <gtest/gtest.h>
#include <roislam/evaluation/CErrorPlot.h>
#include <roislam/evaluation/CTrajectoryEvaluator.h>
#include <roislam/testing/TestData.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;
using roislam::evaluation::CErrorPlot;

namespace
{
roislam::evaluation::TEvaluationResult evaluation()
{
  roislam::io::TTrajectory gt, est;
  for (int k = 0; k < 300; ++k)
  {
    const double t = 1000 + k / 30.0;
    const mrpt::poses::CPose3D p(std::cos(t), std::sin(t), 1.5, t, 0.1, 0);
    gt.push_back({t, p});
    // An error that grows in the middle of the run.
    const double e = 0.01 + 0.05 * std::exp(-std::pow((k - 150) / 30.0, 2));
    est.push_back({t, mrpt::poses::CPose3D(e, -e, 0, 0.01 * e, 0, 0) + p});
  }
  return roislam::evaluation::CTrajectoryEvaluator().evaluate(gt, est);
}

bool haveGnuplot()
{
  return std::system("gnuplot --version > /dev/null 2>&1") == 0;
}
}  // namespace

TEST(ErrorPlot, WritesANonEmptyPng)
{
  if (!haveGnuplot())
    GTEST_SKIP() << "gnuplot not installed (Debian package gnuplot-nox)";
  const auto dir = roislam::testing::makeTempDir("eval_errplot");
  const std::string png = dir + "/errors.png";
  CErrorPlot::TOptions o;
  o.title = "it's a run";
  CErrorPlot(o).plot(png, evaluation());
  ASSERT_TRUE(fs::exists(png));
  std::ifstream in(png, std::ios::binary);
  char sig[4] = {};
  in.read(sig, 4);
  EXPECT_EQ(std::string(sig + 1, 3), "PNG");
  EXPECT_GT(fs::file_size(png), 10000u);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
  fs::remove_all(dir);
}

TEST(ErrorPlot, ClearErrors)
{
  const auto dir = roislam::testing::makeTempDir("eval_errplot_err");
  EXPECT_THROW(CErrorPlot().plot(dir + "/x.png", {}), std::runtime_error);  // no samples
  CErrorPlot::TOptions o;
  o.gnuplot = "roislam-no-such-gnuplot";
  try
  {
    CErrorPlot(o).plot(dir + "/x.png", evaluation());
    ADD_FAILURE() << "no exception";
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_NE(std::string(e.what()).find("gnuplot-nox"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir + "/x.png"));
  o = CErrorPlot::TOptions();
  o.width = 0;
  EXPECT_THROW(CErrorPlot{o}, std::invalid_argument);
  if (haveGnuplot())
    EXPECT_THROW(CErrorPlot().plot(dir + "/missing/dir/z.png", evaluation()), std::runtime_error);
  fs::remove_all(dir);
}
