// COpenNI2FrameSource on the shared Kinect v1 recording (12 frames, depth not
// registered to colour): read through OpenNI2, its depth registered with the
// sensor description (config/sensor-kinect1.ini), the same frames as the
// rawlog tum2rawlog makes of it; a live device that is absent gives one line.
#include <gtest/gtest.h>
#include <roislam/io/COpenNI2FrameSource.h>
#include <roislam/io/CTum2RawlogApp.h>
#include <roislam/io/CameraPresets.h>
#include <roislam/testing/TestData.h>

#include <cmath>
#include <filesystem>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace
{
std::string sharedOni()
{
  return roislam::testing::sharedDataDir() + "/oni/kinect1_room_12frames.oni";
}

std::string kinectDescription()
{
  return roislam::testing::sourceDir() + "/config/sensor-kinect1.ini";
}

#define REQUIRE_SHARED_ONI(var)        \
  const std::string var = sharedOni(); \
  if (!fs::is_regular_file(var))       \
  GTEST_SKIP() << var << " not found (shared data absent): OpenNI2 recording checks skipped"
}  // namespace

TEST(OpenNI2FrameSource, UnregisteredRecordingNeedsADescription)
{
  REQUIRE_SHARED_ONI(oni);
  try
  {
    roislam::io::CFrameSource::open(oni, "auto");
    ADD_FAILURE() << "an unregistered recording without description was accepted";
  }
  catch (const std::runtime_error& e)
  {
    const std::string what = e.what();
    EXPECT_NE(what.find("not registered"), std::string::npos) << what;
    EXPECT_NE(what.find("--camera"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

TEST(OpenNI2FrameSource, ReadsTwelveFramesWithDepthRegisteredByTheDescription)
{
  REQUIRE_SHARED_ONI(oni);
  const auto sensor = roislam::io::loadSensorFile(kinectDescription());

  // The raw observations (depth on the IR camera's grid), read first: two
  // devices playing one recording at once disturb OpenNI2's file driver.
  std::vector<mrpt::obs::CObservation3DRangeScan::Ptr> raw;
  {
    roislam::io::COpenNI2FrameSource rawSource(
        oni, roislam::io::resolveSensor(kinectDescription(), "."));
    while (auto obs = rawSource.nextObservation())
      raw.push_back(obs);
  }
  ASSERT_EQ(raw.size(), 12u);
  auto source = roislam::io::CFrameSource::open(oni, kinectDescription());
  EXPECT_EQ(source->size(), 12u);
  EXPECT_EQ(source->name(), "kinect1_room_12frames");
  EXPECT_EQ(source->sensor().sensor.name, "kinect1");
  EXPECT_FALSE(source->sensor().sensor.depth_registered);
  EXPECT_DOUBLE_EQ(source->sensor().sensor.depth_scale, 1000);  // DEPTH_1_MM
  std::size_t frames = 0;
  double lastStamp = -1;
  while (auto f = source->next())
  {
    ASSERT_LT(frames, raw.size());
    const auto& obs = raw[frames];
    EXPECT_EQ(f->index, frames);
    EXPECT_EQ(f->rgb.type(), CV_8UC3);
    EXPECT_EQ(f->rgb.cols, 640);
    EXPECT_EQ(f->depth.type(), CV_32FC1);
    EXPECT_EQ(f->depth.rows, 480);
    if (frames > 0)
    {
      EXPECT_NEAR(f->timestamp - lastStamp, 1 / 30.0, 0.002);
    }
    lastStamp = f->timestamp;
    EXPECT_NEAR(obs->rangeUnits, 0.001, 1e-9);
    EXPECT_DOUBLE_EQ(obs->cameraParams.fx(), sensor.depth.fx());
    EXPECT_DOUBLE_EQ(obs->cameraParamsIntensity.fx(), sensor.colour.fx());

    // Every raw reading lands where the description says: the depth camera's
    // ray, moved by depth_pose_in_colour, projected by the colour camera.
    // The z-buffer keeps the nearest reading of a colour pixel.
    const auto& dc = sensor.depth;
    const auto& cc = sensor.colour;
    int checked = 0, exact = 0, samePixel = 0, behind = 0;
    for (int v = 0; v < 480; v += 4)
      for (int u = 0; u < 640; u += 4)
      {
        const double z = obs->rangeImage(v, u) * 0.001;
        if (!(z > 0))
          continue;
        double X, Y, Z;
        sensor.depth_pose_in_colour.composePoint(
            (u - dc.cx()) * z / dc.fx(), (v - dc.cy()) * z / dc.fy(), z, X, Y, Z);
        const int cu = static_cast<int>(std::lround(cc.fx() * X / Z + cc.cx()));
        const int cv = static_cast<int>(std::lround(cc.fy() * Y / Z + cc.cy()));
        if (cu < 0 || cv < 0 || cu >= 640 || cv >= 480)
          continue;
        ++checked;
        const float reg = f->depth.at<float>(cv, cu);
        exact += std::abs(reg - Z) < 1e-6;
        behind += reg > Z + 1e-6;  // a farther reading kept: never
        samePixel += std::abs(f->depth.at<float>(v, u) - z) < 1e-6;
      }
    ASSERT_GT(checked, 5000);
    // cv::rgbd::registerDepth projects in float: a reading on a half-pixel
    // boundary can land one pixel off this double-precision projection,
    // leaving this pixel to a farther reading (1 in ~16000 measured).
    EXPECT_LE(behind, checked / 1000);
    EXPECT_GT(exact, 0.9 * checked);
    // The registration moved the readings (about 575 x 2.5 cm / z px sideways).
    EXPECT_LT(samePixel, 0.5 * checked);
    ++frames;
  }
  EXPECT_EQ(frames, 12u);
  // rewind() plays the recording again from the start.
  source->rewind();
  const auto first = source->next();
  ASSERT_TRUE(first);
  EXPECT_EQ(first->index, 0u);
}

TEST(OpenNI2FrameSource, RecordingAndItsRawlogGiveTheSameFrames)
{
  REQUIRE_SHARED_ONI(oni);
  const fs::path dir = roislam::testing::makeTempDir("oni_rawlog");
  roislam::io::CTum2RawlogApp::TOptions o;
  o.input = oni;
  o.output = (dir / "room.rawlog").string();
  o.camera = kinectDescription();
  const auto r = roislam::io::CTum2RawlogApp(o).run();
  EXPECT_EQ(r.frames, 12u);
  ASSERT_TRUE(r.sensorFile);
  EXPECT_EQ(*r.sensorFile, (dir / "room.camera.ini").string());

  auto fromOni = roislam::io::CFrameSource::open(oni, kinectDescription());
  // --camera auto: the description written beside the rawlog is picked up.
  auto fromRawlog = roislam::io::CFrameSource::open(o.output, "auto");
  EXPECT_NE(fromRawlog->sensor().reason.find("room.camera.ini"), std::string::npos)
      << fromRawlog->sensor().reason;
  EXPECT_DOUBLE_EQ(fromRawlog->sensor().sensor.rolling_shutter_ms, 25);
  EXPECT_FALSE(fromRawlog->sensor().sensor.depth_registered);
  ASSERT_EQ(fromRawlog->size(), 12u);
  std::size_t n = 0;
  while (auto a = fromOni->next())
  {
    const auto b = fromRawlog->next();
    ASSERT_TRUE(b);
    EXPECT_EQ(cv::norm(a->rgb, b->rgb, cv::NORM_INF), 0.0) << n;
    EXPECT_EQ(cv::norm(a->depth, b->depth, cv::NORM_INF), 0.0) << n;
    EXPECT_NEAR(a->timestamp, b->timestamp, 1e-5);
    EXPECT_GT(cv::countNonZero(a->depth), 100000) << n;
    ++n;
  }
  EXPECT_EQ(n, 12u);
  EXPECT_FALSE(fromRawlog->next());
  fs::remove_all(dir);
}

TEST(OpenNI2FrameSource, AbsentDeviceIsOneLine)
{
  for (const std::string input : {"openni2", "openni2://no-such-device"})
  {
    try
    {
      roislam::io::CFrameSource::open(input, "auto");
      GTEST_SKIP() << input << ": a device is attached; the no-device message is not checked";
    }
    catch (const std::runtime_error& e)
    {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(input + ": no OpenNI2 device found", 0), 0u) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
  // tum2rawlog refuses a live device without a frame limit before opening it.
  roislam::io::CTum2RawlogApp::TOptions o;
  o.input = "openni2";
  o.output = roislam::testing::makeTempDir("oni_live") + "/live.rawlog";
  EXPECT_THROW(roislam::io::CTum2RawlogApp(o).run(), std::exception);
}
