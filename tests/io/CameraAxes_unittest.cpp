/* Cameras with a negative focal length (CameraAxes.h): the flipped image and
 * the camera with positive focal lengths describe the same rays; the sensor
 * description reads and checks them; ICL-NUIM folders get the icl preset; the
 * readers deliver flipped frames with the positive camera. */
#include <roislam/io/CTumFrameSource.h>
#include <roislam/io/CameraAxes.h>
#include <roislam/io/CameraPresets.h>
#include <roislam/testing/TestData.h>

#include <filesystem>
#include <fstream>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>

#include "TumFolderFixture.h"

namespace fs = std::filesystem;
using namespace roislam::io;

namespace
{
mrpt::img::TCamera distortedCamera(double fx, double fy)
{
  mrpt::img::TCamera c = cameraPreset("fr1");  // plumb_bob, p1 and p2 non-zero
  c.setIntrinsicParamsFromValues(fx, fy, 300.25, 250.75);
  return c;
}

/** The normalised, undistorted ray of pixel (u, v) (OpenCV's model, which
 *  is MRPT's plumb_bob). */
cv::Point2d ray(const mrpt::img::TCamera& c, double u, double v)
{
  const cv::Matx33d K(c.fx(), 0, c.cx(), 0, c.fy(), c.cy(), 0, 0, 1);
  std::vector<double> dist(c.dist.begin(), c.dist.end());
  std::vector<cv::Point2d> in{{u, v}}, out;
  cv::undistortPoints(in, out, K, dist);
  return out[0];
}
}  // namespace

TEST(CameraAxes, FlippedPixelsWithPositiveFocalLengthsAreTheSameRays)
{
  for (const auto& [fx, fy] :
       std::vector<std::pair<double, double>>{{517.3, -516.5}, {-517.3, 516.5}, {-517.3, -516.5}})
  {
    const auto declared = distortedCamera(fx, fy);
    ASSERT_TRUE(hasNegativeFocalLength(declared));
    const auto positive = withPositiveFocalLengths(declared);
    EXPECT_GT(positive.fx(), 0);
    EXPECT_GT(positive.fy(), 0);
    EXPECT_FALSE(hasNegativeFocalLength(positive));
    for (double u : {3.0, 200.5, 631.0})
      for (double v : {7.0, 240.0, 470.5})
      {
        const double uf = fx < 0 ? declared.ncols - 1 - u : u;
        const double vf = fy < 0 ? declared.nrows - 1 - v : v;
        const cv::Point2d a = ray(declared, u, v), b = ray(positive, uf, vf);
        EXPECT_NEAR(a.x, b.x, 1e-9) << fx << " " << fy << " at " << u << "," << v;
        EXPECT_NEAR(a.y, b.y, 1e-9) << fx << " " << fy << " at " << u << "," << v;
      }
  }
  const auto plain = distortedCamera(517.3, 516.5);
  EXPECT_FALSE(hasNegativeFocalLength(plain));
  EXPECT_EQ(withPositiveFocalLengths(plain).intrinsicParams, plain.intrinsicParams);
}

TEST(CameraAxes, FlipsOnlyTheAxesWithNegativeFocalLength)
{
  cv::Mat img(480, 640, CV_8UC1, cv::Scalar(0));
  img.at<uint8_t>(10, 20) = 255;
  const auto at = [](const cv::Mat& m)
  {
    cv::Point p;
    cv::minMaxLoc(m, nullptr, nullptr, nullptr, &p);
    return p;
  };
  for (const auto& [fx, fy, expected] : std::vector<std::tuple<double, double, cv::Point>>{
           {500, 500, {20, 10}},
           {500, -500, {20, 469}},
           {-500, 500, {619, 10}},
           {-500, -500, {619, 469}}})
  {
    cv::Mat m = img.clone();
    flipToPositiveFocalLengths(m, distortedCamera(fx, fy));
    EXPECT_EQ(at(m), expected) << fx << " " << fy;
  }
}

TEST(CameraAxes, SensorDescriptionKeepsANegativeFocalLength)
{
  // MRPT 2.5 alone reads fy = -480 as a normalised focal length (x 480).
  TSensorDescription d = sensorPreset("icl");
  EXPECT_DOUBLE_EQ(d.colour.fy(), -480.0);
  EXPECT_DOUBLE_EQ(d.colour.fx(), 481.2);
  EXPECT_EQ(d.rolling_shutter_ms, 0);
  EXPECT_EQ(d.depth_noise.model, "disparity");
  const std::string dir = roislam::testing::makeTempDir("camera_axes");
  const std::string file = dir + "/icl.ini";
  std::ofstream(file) << d.toIniText();
  const TSensorDescription back = loadSensorFile(file);
  EXPECT_DOUBLE_EQ(back.colour.fy(), -480.0);
  EXPECT_DOUBLE_EQ(back.colour.fx(), 481.2);
  EXPECT_DOUBLE_EQ(back.colour.cy(), 239.5);

  // A plain calibration with fy < 0, too.
  std::ofstream(dir + "/plain.ini") << "[CAMERA_PARAMS]\nresolution = [640 480]\ncx = 319.5\n"
                                       "cy = 239.5\nfx = 481.2\nfy = -480\ndist = [0 0 0 0 0]\n";
  EXPECT_DOUBLE_EQ(loadSensorFile(dir + "/plain.ini").colour.fy(), -480.0);

  // Zero is no camera.
  std::ofstream(dir + "/zero.ini") << "[CAMERA_PARAMS]\nresolution = [640 480]\ncx = 319.5\n"
                                      "cy = 239.5\nfx = 481.2\nfy = 0\ndist = [0 0 0 0 0]\n";
  try
  {
    loadSensorFile(dir + "/zero.ini");
    ADD_FAILURE() << "fy = 0 accepted";
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_NE(std::string(e.what()).find("zero.ini"), std::string::npos) << e.what();
  }

  // The rolling shutter runs the other way in the flipped frames.
  d.rolling_shutter_ms = 20;
  EXPECT_DOUBLE_EQ(d.signedReadoutMs(), 20);
  EXPECT_DOUBLE_EQ(d.frameReadoutMs(), -20);
  d.colour.setIntrinsicParamsFromValues(481.2, 480, 319.5, 239.5);
  EXPECT_DOUBLE_EQ(d.frameReadoutMs(), 20);
  fs::remove_all(dir);
}

TEST(CameraAxes, UnregisteredCamerasShareOneAxisConvention)
{
  TSensorDescription d = sensorPreset("icl");
  d.depth_registered = false;
  d.depth = d.colour;
  EXPECT_NO_THROW(d.validate());
  d.depth.setIntrinsicParamsFromValues(575, 575, 319.5, 239.5);
  try
  {
    d.validate();
    ADD_FAILURE() << "a y-up colour camera with a y-down depth camera was accepted";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("[DEPTH_CAMERA_PARAMS] fy"), std::string::npos)
        << e.what();
  }
}

TEST(CameraAxes, IclFolderNamesPickTheIclPreset)
{
  const std::string root = roislam::testing::makeTempDir("camera_axes_names");
  for (const char* name :
       {"living_room_traj2_frei_png", "icl_lr_kt2", "ICL-NUIM-of-kt1", "office_room_traj0",
        "traj3_frei_png"})
  {
    fs::create_directories(root + "/" + name);
    const auto choice = resolveSensor("auto", root + "/" + name);
    EXPECT_EQ(choice.source, "preset icl") << name << ": " << choice.reason;
    EXPECT_DOUBLE_EQ(choice.sensor.colour.fy(), -480.0);
  }
  for (const char* name : {"bicycle_room", "rgbd_dataset_freiburg1_xyz", "my_room"})
  {
    fs::create_directories(root + "/" + name);
    EXPECT_NE(resolveSensor("auto", root + "/" + name).source, "preset icl") << name;
  }
  EXPECT_EQ(resolveSensor("icl", root).source, "preset icl");
  fs::remove_all(root);
}

TEST(CameraAxes, TumReaderDeliversFlippedFramesWithThePositiveCamera)
{
  // Two 16 x 12 frames; the declared camera has fy < 0.
  const std::string root = roislam::testing::makeTempDir("camera_axes_tum");
  const std::string dir =
      roislam::iotest::writeTumFolder(root, "seq", {1.0, 2.0}, {1.0, 2.0}, 16, 12);
  TSensorDescription d;
  d.name = "y-up";
  d.colour = roislam::iotest::smallCamera(16, 12);
  d.colour.setIntrinsicParamsFromValues(20.0, -21.0, 7.5, 4.0);
  std::ofstream(dir + "/camera.ini") << d.toIniText();
  CTumFrameSource src(dir, resolveSensor("auto", dir), CTumFrameSource::TOptions());
  EXPECT_DOUBLE_EQ(src.sensor().sensor.colour.fy(), -21.0);
  EXPECT_DOUBLE_EQ(src.camera().fy(), 21.0);
  EXPECT_DOUBLE_EQ(src.camera().cy(), 11 - 4.0);
  const auto f = src.next();
  ASSERT_TRUE(f);
  EXPECT_DOUBLE_EQ(f->camera.fy(), 21.0);
  EXPECT_DOUBLE_EQ(f->camera.cy(), 7.0);
  cv::Mat rgb, depth;
  cv::flip(roislam::iotest::colourImage(16, 12, 0), rgb, 0);
  cv::flip(roislam::iotest::depthImage(16, 12, 0), depth, 0);
  EXPECT_EQ(cv::norm(f->rgb, rgb, cv::NORM_INF), 0);
  cv::Mat depthM;
  depth.convertTo(depthM, CV_32F, 1.0 / 5000);
  EXPECT_LT(cv::norm(f->depth, depthM, cv::NORM_INF), 1e-6);
  fs::remove_all(root);
}
