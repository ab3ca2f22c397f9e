// CTrajectoryPlot: PNG through gnuplot; clear errors when gnuplot is missing
// or the output cannot be written.
#include <gtest/gtest.h>
#include <roislam/evaluation/CTrajectoryPlot.h>
#include <roislam/testing/TestData.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

using roislam::evaluation::CTrajectoryPlot;
using roislam::io::TPoseStamped;
using roislam::io::TTrajectory;

namespace
{
namespace fs = std::filesystem;

TTrajectory circle(double radius, double height, double from, double to)
{
  TTrajectory t;
  for (double s = from; s < to; s += 0.1)
    t.push_back(TPoseStamped{
        1000 + s,
        mrpt::poses::CPose3D(
            radius * std::cos(s), radius * std::sin(s), height + 0.05 * std::sin(3 * s), s, 0, 0)});
  return t;
}

bool havePngSignature(const std::string& file)
{
  std::ifstream in(file, std::ios::binary);
  char sig[8] = {};
  in.read(sig, 8);
  return in && sig[0] == '\x89' && sig[1] == 'P' && sig[2] == 'N' && sig[3] == 'G';
}

bool haveGnuplot()
{
  return std::system("gnuplot --version > /dev/null 2>&1") == 0;
}
}  // namespace

TEST(TrajectoryPlot, GroundTruthAndSeveralNamedEstimates)
{
  if (!haveGnuplot())
    GTEST_SKIP() << "gnuplot not installed (Debian package gnuplot-nox)";
  const auto dir = roislam::testing::makeTempDir("eval_plot");
  CTrajectoryPlot::TOptions o;
  o.title = "fr1/xyz: ground truth vs the three versions";
  const std::string png = dir + "/it's a plot.png";  // quote in the name on purpose
  TTrajectory withGap = circle(1.05, 1.5, 0, 3);
  const TTrajectory after = circle(1.05, 1.5, 5, 6.3);
  withGap.insert(withGap.end(), after.begin(), after.end());
  CTrajectoryPlot(o).plot(
      png, circle(1.0, 1.5, 0, 6.3),
      {{"traditional", circle(1.1, 1.52, 0, 6.3)},
       {"small_ROI (gap)", withGap},
       {"big ROI", {}}});  // a version that produced no trajectory
  ASSERT_TRUE(fs::exists(png));
  EXPECT_TRUE(havePngSignature(png));
  EXPECT_GT(fs::file_size(png), 10000u);
  // Only the PNG is left behind.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
  fs::remove_all(dir);
}

TEST(TrajectoryPlot, ClearErrors)
{
  const auto dir = roislam::testing::makeTempDir("eval_plot_err");
  CTrajectoryPlot::TOptions o;
  o.gnuplot = "roislam-no-such-gnuplot";
  try
  {
    CTrajectoryPlot(o).plot(dir + "/x.png", circle(1, 1, 0, 3), {});
    ADD_FAILURE() << "no exception";
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_NE(std::string(e.what()).find("gnuplot-nox"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir + "/x.png"));
  EXPECT_THROW(CTrajectoryPlot().plot(dir + "/y.png", {}, {{"a", {}}}), std::runtime_error);
  o.up_axis = "w";
  EXPECT_THROW(CTrajectoryPlot{o}, std::invalid_argument);
  if (haveGnuplot())
  {
    EXPECT_THROW(
        CTrajectoryPlot().plot(dir + "/missing/dir/z.png", circle(1, 1, 0, 3), {}),
        std::runtime_error);
  }
  fs::remove_all(dir);
}

namespace
{
/** Camera pose (optical convention) from its forward (z) and right (x) axes in the world. */
mrpt::poses::CPose3D camera(const Eigen::Vector3d& forward, const Eigen::Vector3d& right)
{
  mrpt::math::CMatrixDouble33 R;
  const Eigen::Vector3d down = forward.cross(right);
  for (int a = 0; a < 3; ++a)
  {
    R(a, 0) = right[a];
    R(a, 1) = down[a];
    R(a, 2) = forward[a];
  }
  mrpt::math::CVectorFixedDouble<3> t;
  t.fill(0);
  return mrpt::poses::CPose3D(R, t);
}
}  // namespace

TEST(TrajectoryPlot, AutoUpAxisFollowsTheCameraOrientation)
{
  TTrajectory level, floor, opticalWorld;
  for (int k = 0; k < 100; ++k)
  {
    const double yaw = 0.03 * k;  // turning on the spot: positions say nothing
    const Eigen::Vector3d right(std::cos(yaw), std::sin(yaw), 0);
    // Hand-held in a z-up world, slightly pitched and rolled.
    level.push_back(TPoseStamped{
        double(k), camera(Eigen::Vector3d(-std::sin(yaw), std::cos(yaw), 0), right) +
                       mrpt::poses::CPose3D(0, 0, 0, 0, 0.1 * std::sin(0.2 * k), 0.05)});
    // Looking down at the floor (fr1/floor).
    floor.push_back(TPoseStamped{double(k), camera(Eigen::Vector3d(0, 0, -1), right)});
    // World = first camera frame (y down), small rotations.
    opticalWorld.push_back(
        TPoseStamped{double(k), mrpt::poses::CPose3D(0, 0, 0, 0.2 * std::sin(0.1 * k), 0.1, 0.02)});
  }
  EXPECT_EQ(CTrajectoryPlot::autoUpAxis(level), 2);
  EXPECT_EQ(CTrajectoryPlot::autoUpAxis(floor), 2);
  EXPECT_EQ(CTrajectoryPlot::autoUpAxis(opticalWorld), 1);
  EXPECT_EQ(CTrajectoryPlot::autoUpAxis({}), 2);
}
