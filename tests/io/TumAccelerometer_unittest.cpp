/* TUM accelerometer logs: read as the benchmark writes them, written back
 * exactly, one-line errors naming file and line; the Kinect's axes. */
#include <gtest/gtest.h>
#include <roislam/io/TumAccelerometer.h>
#include <roislam/testing/TestData.h>

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;
using roislam::io::loadTumAccelerometer;

TEST(TumAccelerometer, ReadsTheBenchmarkLayoutSortedAndSkipsNan)
{
  const auto dir = roislam::testing::makeTempDir("io_accel");
  const std::string file = dir + "/accelerometer.txt";
  std::ofstream(file) << "# accelerometer data\n# file: 'x.bag'\n# timestamp ax ay az\n"
                         "1305031101.177330 0.107765 7.914769 -6.274340\n"
                         "1305031101.176190,0.1,7.9,-6.2\n"
                         "1305031101.2 nan 1 2\n\n";
  const auto log = loadTumAccelerometer(file);
  ASSERT_EQ(log.size(), 2u);
  EXPECT_DOUBLE_EQ(log[0].timestamp, 1305031101.176190);
  EXPECT_DOUBLE_EQ(log[1].acceleration.y, 7.914769);
  EXPECT_DOUBLE_EQ(log[1].acceleration.z, -6.274340);

  const std::string copy = dir + "/copy.txt";
  roislam::io::saveTumAccelerometer(copy, log, "a copy");
  const auto back = loadTumAccelerometer(copy);
  ASSERT_EQ(back.size(), log.size());
  for (std::size_t i = 0; i < log.size(); ++i)
  {
    EXPECT_EQ(back[i].timestamp, log[i].timestamp);
    EXPECT_EQ(back[i].acceleration, log[i].acceleration);
  }
  fs::remove_all(dir);
}

TEST(TumAccelerometer, OneLineErrorsNameFileAndLine)
{
  const auto dir = roislam::testing::makeTempDir("io_accel_err");
  const std::string file = dir + "/accelerometer.txt";
  auto expectError = [&](const std::string& text, const std::string& part)
  {
    std::ofstream(file) << text;
    try
    {
      loadTumAccelerometer(file);
      ADD_FAILURE() << "no error for " << text;
    }
    catch (const std::runtime_error& e)
    {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  expectError("# c\n1 2 3\n", file + ":2: expected 4 values (timestamp ax ay az), found 3");
  expectError("1 2 3 x\n", file + ":1: not a number: 'x'");
  expectError("1 2 3 inf\n", file + ":1: infinite value");
  try
  {
    loadTumAccelerometer(dir + "/none.txt");
    ADD_FAILURE();
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_EQ(std::string(e.what()), dir + "/none.txt: cannot open");
  }
  fs::remove_all(dir);
}

TEST(TumAccelerometer, KinectAxesAreTheOpticalOnesTurnedAboutZ)
{
  // At rest, level, looking ahead: the optical y axis points down, so "up"
  // is optical -y, which the Kinect reads as +y (as fr1's first samples do).
  const auto up = roislam::io::accelerometerToOptical({0, 9.81, 0});
  EXPECT_EQ(up, mrpt::math::TVector3D(0, -9.81, 0));
  EXPECT_EQ(roislam::io::accelerometerToOptical({1, 2, 3}), mrpt::math::TVector3D(-1, -2, 3));
}
