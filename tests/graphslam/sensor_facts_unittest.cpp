/* SensorFacts.h: the camera facts both SLAM apps take from the sensor
 * description (readout, depth-noise model, common keypoint shift, keypoint noise); a readout the
 * ini still sets wins, with a note when it differs; iniSetsReadout() finds the key in either ini
 * layout. */
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <roislam/graphslam/SensorFacts.h>

#include <string>
#include <vector>

namespace graphslam = roislam::graphslam;

namespace
{
roislam::io::TSensorChoice globalShutterDisparity()
{
  roislam::io::TSensorChoice c;
  c.sensor.rolling_shutter_ms = 0;
  c.sensor.depth_noise.model = "disparity";
  c.sensor.common_pixel_sigma_px = 0.7;
  c.sensor.keypoint_sigma_px = 0.6;
  c.sensor.keypoint_time_sigma_ms = 2.5;
  c.source = "file camera.ini";
  c.reason = "camera.ini in the folder";
  return c;
}
}  // namespace

TEST(SensorFacts, TheSensorsReadoutAndDepthNoiseUnlessTheIniSetsTheReadout)
{
  std::vector<std::string> lines;
  const auto progress = [&lines](const std::string& l) { lines.push_back(l); };
  roislam::frontend::CRgbdOdometry::TOptions fe;
  fe.rolling_shutter_ms = 25;
  graphslam::applySensorFacts(fe, globalShutterDisparity(), false, "app", "m.ini", progress);
  EXPECT_EQ(fe.rolling_shutter_ms, 0.0);
  EXPECT_EQ(fe.depth_noise.model, "disparity");
  EXPECT_EQ(fe.common_pixel_sigma_px, 0.7);
  EXPECT_EQ(fe.keypoint_sigma_px, 0.6);
  EXPECT_EQ(fe.keypoint_time_sigma_ms, 2.5);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0].rfind("app: ", 0), 0u);

  lines.clear();
  fe = {};
  fe.rolling_shutter_ms = 25;
  graphslam::applySensorFacts(fe, globalShutterDisparity(), true, "app", "m.ini", progress);
  EXPECT_EQ(fe.rolling_shutter_ms, 25.0);
  EXPECT_EQ(fe.depth_noise.model, "disparity");
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_NE(lines[1].find("m.ini sets rolling_shutter_ms = 25"), std::string::npos) << lines[1];
  EXPECT_EQ(graphslam::readoutOrigin(true), "ini");
  EXPECT_EQ(graphslam::readoutOrigin(false), "sensor description");
}

TEST(SensorFacts, IniSetsReadoutInEitherLayout)
{
  mrpt::config::CConfigFileMemory roi, engine, none;
  roi.write("FrontEnd", "rolling_shutter_ms", 25);
  engine.write("NodeRegistrationDeciderParameters", "rolling_shutter_ms", 25);
  none.write("FrontEnd", "mode", "traditional");
  EXPECT_TRUE(graphslam::iniSetsReadout(roi, "roi.ini"));
  EXPECT_TRUE(graphslam::iniSetsReadout(engine, "engine.ini"));
  EXPECT_FALSE(graphslam::iniSetsReadout(none, "none.ini"));
}
