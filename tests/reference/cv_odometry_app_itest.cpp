// cv-odometry end to end on the synthetic textured loop (ground truth known):
// trajectory and summary written, an accuracy bound per method, one-line errors.
#include <gtest/gtest.h>
#include <roislam/io/TumTrajectory.h>
#include <roislam/reference/CCvOdometryApp.h>
#include <roislam/testing/TestData.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

using roislam::reference::CCvOdometryApp;
namespace fs = std::filesystem;

TEST(CCvOdometryApp, syntheticLoopEveryMethod)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "textured");
  const std::string out = roislam::testing::makeTempDir("cvodo");
  for (const std::string method : {"rgbd", "icp", "rgbdicp"})
  {
    CCvOdometryApp::TArguments a;
    a.input = seq;
    a.outputDir = out + "/" + method;
    a.method = method;
    a.maxFrames = 40;
    const auto s = CCvOdometryApp(a).run();
    EXPECT_EQ(s.frames, 40u);
    EXPECT_EQ(s.failedFrames, 0u) << method;
    ASSERT_TRUE(s.ateRmse) << method;
    // Measured on the 25 ms rolling-shutter loop: 8-20 mm; the bound catches
    // a wrong pose composition (inverted motion gives decimetres).
    EXPECT_LT(*s.ateRmse, 0.04) << method;
    EXPECT_GT(s.msPerFrame, 0);
    EXPECT_EQ(roislam::io::loadTumTrajectory(a.outputDir + "/trajectory.txt").size(), 40u);
    std::ifstream js(a.outputDir + "/summary.json");
    const auto j = nlohmann::json::parse(js);
    EXPECT_EQ(j.at("method"), method);
    EXPECT_NEAR(j.at("ate_rmse").get<double>(), *s.ateRmse, 1e-12);
    EXPECT_TRUE(j.at("ms_per_frame").is_number());
  }
  fs::remove_all(out);
}

TEST(CCvOdometryApp, badIniAndInputGiveOneLineErrors)
{
  const std::string dir = roislam::testing::makeTempDir("cvodo_bad");
  std::ofstream(dir + "/bad.ini") << "[CvOdometry]\nmax_depht = 3\n";
  std::ofstream(dir + "/badvalue.ini") << "[CvOdometry]\nmax_depth = -3\n";
  CCvOdometryApp::TArguments a;
  a.input = dir;
  a.outputDir = dir + "/out";
  a.iniFile = dir + "/bad.ini";
  try
  {
    CCvOdometryApp app(a);
    FAIL() << "unknown key accepted";
  }
  catch (const std::exception& e)
  {
    EXPECT_NE(std::string(e.what()).find("max_depht"), std::string::npos) << e.what();
  }
  a.iniFile = dir + "/badvalue.ini";
  try
  {
    CCvOdometryApp app(a);
    FAIL() << "bad value accepted";
  }
  catch (const std::exception& e)
  {
    EXPECT_NE(std::string(e.what()).find("[CvOdometry] max_depth"), std::string::npos) << e.what();
  }
  // The executable: a missing input is one line and exit code 1.
  const std::string exe = roislam::testing::binaryDir() + "/apps/cv-odometry/cv-odometry";
  const std::string cmd = "'" + exe + "' --input '" + dir + "/nothing' --output-dir '" + dir +
                          "/o' 2> '" + dir + "/err.txt'";
  const int status = std::system(cmd.c_str());
  EXPECT_NE(status, 0);
  std::ifstream e(dir + "/err.txt");
  std::string line, all;
  int lines = 0;
  while (std::getline(e, line))
  {
    ++lines;
    all += line;
  }
  EXPECT_EQ(lines, 1) << all;
  EXPECT_NE(all.find("cv-odometry: error:"), std::string::npos) << all;
  fs::remove_all(dir);
}
