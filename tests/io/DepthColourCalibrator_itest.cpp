/* CDepthColourCalibrator on a rendered 7-Scenes-like sequence (ctest fixture
 * "sevenscenes": the 7scenes preset's cameras, depth not registered), whose
 * true registration is the preset's: started from it, the start is kept;
 * started from cameras centimetres, tenths of a degree and pixels off, it
 * comes back within a pixel and is used. On the shared Kinect v1 recording
 * (real edges), through the calibrator and the recording reader; a flat
 * wall; bad input; the folder reader. */
#include <gtest/gtest.h>
#include <mrpt/core/bits_math.h>
#include <roislam/io/CDepthColourCalibrator.h>
#include <roislam/io/COpenNI2FrameSource.h>
#include <roislam/io/CTumFrameSource.h>
#include <roislam/io/CameraPresets.h>
#include <roislam/io/ObservationConversion.h>
#include <roislam/io/SevenScenes.h>
#include <roislam/testing/TestData.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <vector>

using roislam::io::CDepthColourCalibrator;

namespace
{
CDepthColourCalibrator::TResult calibrate(
    const std::string& seq, const roislam::io::TSensorDescription& start,
    const CDepthColourCalibrator::TOptions& options = {})
{
  CDepthColourCalibrator calibrator(start, options);
  const auto frames = roislam::io::listSevenScenesFrames(seq);
  for (std::size_t i = 0; i < frames.size(); i += 3)
  {
    const cv::Mat rgb = cv::imread(frames[i].colourFile, cv::IMREAD_COLOR);
    const cv::Mat raw = cv::imread(frames[i].depthFile, cv::IMREAD_UNCHANGED);
    cv::Mat depth;
    raw.convertTo(depth, CV_32F, 1.0 / start.depth_scale);
    depth.setTo(0, raw == 65535);
    calibrator.addFrame(rgb, depth);
  }
  const auto result = calibrator.estimate();
  std::printf("%s\n", result.summary().c_str());
  return result;
}

/** RMS distance (px) between where two descriptions land the same depth
 *  readings in the colour image (each through its colour distortion): a
 *  grid over the depth image at 1, 2, 4 m. */
double projectionRmsPx(
    const roislam::io::TSensorDescription& a, const roislam::io::TSensorDescription& b)
{
  const auto& dc = a.depth;
  std::vector<cv::Point3d> readings;
  for (double z : {1.0, 2.0, 4.0})
    for (int i = 0; i < 8; ++i)
      for (int j = 0; j < 6; ++j)
      {
        const double u = (i + 0.5) * dc.ncols / 8.0, v = (j + 0.5) * dc.nrows / 6.0;
        readings.emplace_back((u - dc.cx()) / dc.fx() * z, (v - dc.cy()) / dc.fy() * z, z);
      }
  std::vector<cv::Point2d> px[2];
  int k = 0;
  for (const auto* s : {&a, &b})
  {
    std::vector<cv::Point3d> inColour;
    for (const auto& p : readings)
    {
      double x, y, w;
      s->depth_pose_in_colour.composePoint(p.x, p.y, p.z, x, y, w);
      inColour.emplace_back(x, y, w);
    }
    const auto& c = s->colour;
    const cv::Matx33d K(c.fx(), 0, c.cx(), 0, c.fy(), c.cy(), 0, 0, 1);
    const std::vector<double> dist(c.dist.begin(), c.dist.end());
    cv::projectPoints(inColour, cv::Vec3d(), cv::Vec3d(), K, dist, px[k++]);
  }
  double sq = 0;
  for (std::size_t i = 0; i < readings.size(); ++i)
    sq += (px[0][i] - px[1][i]).dot(px[0][i] - px[1][i]);
  return std::sqrt(sq / double(readings.size()));
}

}  // namespace

// Started from the true cameras, the estimate lands the readings within the
// method's own error of them, so the start is kept.
TEST(DepthColourCalibrator, KeepsAStartThatIsRight)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "sevenscenes");
  const auto truth = roislam::io::sensorPreset("7scenes");
  const auto r = calibrate(seq, truth);
  EXPECT_FALSE(r.accepted);
  EXPECT_NE(r.reason.find("the start kept"), std::string::npos) << r.reason;
  EXPECT_LT(r.changePx, 1.0);
  EXPECT_LT(r.spreadPx, 0.25);
  EXPECT_EQ(r.sensor.depth_pose_in_colour, truth.depth_pose_in_colour);
  EXPECT_DOUBLE_EQ(r.sensor.colour.fx(), truth.colour.fx());
}

// From cameras centimetres, tenths of a degree and pixels off, it comes
// back to within a pixel of the truth, and is used.
TEST(DepthColourCalibrator, FindsTheRegistrationFromAStartThatIsOff)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "sevenscenes");
  const auto truth = roislam::io::sensorPreset("7scenes");
  auto start = truth;
  start.depth_pose_in_colour = mrpt::poses::CPose3D(
      -0.035, 0.006, -0.002, mrpt::DEG2RAD(0.6), mrpt::DEG2RAD(-0.5), mrpt::DEG2RAD(0.4));
  start.colour.setIntrinsicParamsFromValues(535, 515, 323.5, 236.5);
  const double before = projectionRmsPx(start, truth);
  const auto r = calibrate(seq, start);
  ASSERT_TRUE(r.accepted) << r.reason;
  const double after = projectionRmsPx(r.sensor, truth);
  std::printf("projection error %.2f -> %.2f px\n", before, after);
  EXPECT_GT(before, 8.0);
  EXPECT_LT(after, 0.6);
  EXPECT_LT(r.distanceEstimatePx, 0.3 * r.distanceStartPx);
  EXPECT_LT(
      (r.sensor.depth_pose_in_colour.translation() - truth.depth_pose_in_colour.translation())
          .norm(),
      0.004);
  EXPECT_NEAR(r.sensor.colour.fx() / truth.colour.fx(), 1.0, 0.005);
  EXPECT_NEAR(r.sensor.colour.fy() / truth.colour.fy(), 1.0, 0.005);
  EXPECT_FALSE(r.sensor.estimate_registration);
}

// Behind a Kinect v1 colour lens the preset does not know (the TUM fr1
// camera's distortion, up to 22 px at the corners): the lens's k1, k2 are
// estimated with the registration and the estimate is used. Without them the
// edges pull the focal length and the depth offset along the direction they
// cannot tell apart, and the estimate is not used.
TEST(DepthColourCalibrator, FindsTheColourLens)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "sevenscenes_lens");
  const auto start = roislam::io::sensorPreset("7scenes");
  auto truth = start;
  const double lens[5] = {0.2624, -0.9531, -0.0054, 0.0026, 1.1633};
  std::copy(lens, lens + 5, truth.colour.dist.begin());
  truth.colour.distortion = mrpt::img::DistortionModel::plumb_bob;
  const double before = projectionRmsPx(start, truth);
  const auto r = calibrate(seq, start);
  ASSERT_TRUE(r.accepted) << r.reason;
  const double after = projectionRmsPx(r.sensor, truth);
  std::printf("projection error %.2f -> %.2f px\n", before, after);
  EXPECT_GT(before, 4.0);
  EXPECT_LT(after, 1.0);
  EXPECT_GT(r.estimatedK1, 0.05);
  EXPECT_EQ(r.sensor.colour.distortion, mrpt::img::DistortionModel::plumb_bob);
  EXPECT_DOUBLE_EQ(r.sensor.colour.dist[0], r.estimatedK1);

  CDepthColourCalibrator::TOptions pinhole;
  pinhole.distortion_terms = 0;
  const auto without = calibrate(seq, start, pinhole);
  EXPECT_FALSE(without.accepted);
  EXPECT_NE(without.reason.find("implausible"), std::string::npos) << without.reason;
  EXPECT_DOUBLE_EQ(without.estimatedK1, 0);
}

// A lens whose distortion turns back inside the image (two rays for one
// pixel) is not used, whatever the edges say.
TEST(DepthColourCalibrator, RejectsALensThatFolds)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "sevenscenes");
  auto start = roislam::io::sensorPreset("7scenes");
  start.colour.dist[0] = -1.0;  // the radius peaks at 202 px from the centre
  start.colour.distortion = mrpt::img::DistortionModel::plumb_bob;
  CDepthColourCalibrator::TOptions held;
  held.distortion_terms = 0;
  const auto r = calibrate(seq, start, held);
  EXPECT_FALSE(r.accepted);
  EXPECT_NE(r.reason.find("folds back"), std::string::npos) << r.reason;
}

// The shared Kinect v1 recording (12 frames, described as not registered),
// from config/sensor-kinect1.ini's factory values: a real camera's edges.
TEST(DepthColourCalibrator, RealKinectRecording)
{
  const std::string oni = roislam::testing::sharedDataDir() + "/oni/kinect1_room_12frames.oni";
  if (!std::filesystem::is_regular_file(oni))
    GTEST_SKIP() << oni << " not found (shared data absent)";
  const auto choice =
      roislam::io::resolveSensor(roislam::testing::sourceDir() + "/config/sensor-kinect1.ini", ".");
  CDepthColourCalibrator calibrator(choice.sensor);
  roislam::io::COpenNI2FrameSource source(oni, choice);
  while (auto obs = source.nextObservation())
  {
    calibrator.addFrame(
        obs->intensityImage.asCvMat<cv::Mat>(mrpt::img::SHALLOW_COPY),
        roislam::io::depthMetresOnDepthGrid(*obs, oni));
  }
  const auto r = calibrator.estimate();
  std::printf("%s\n", r.summary().c_str());
  EXPECT_EQ(r.frames, 12u);
  // Whatever the edges say, what is used is plausible for a Kinect v1: the
  // factory values, or an estimate near them.
  const auto& used = r.sensor;
  EXPECT_NEAR(used.colour.fx(), 525, 0.05 * 525);
  EXPECT_NEAR(used.colour.fy(), 525, 0.05 * 525);
  EXPECT_LT(
      (used.depth_pose_in_colour - choice.sensor.depth_pose_in_colour).translation().norm(), 0.02);
  if (!r.accepted)
  {
    EXPECT_EQ(used.depth_pose_in_colour, choice.sensor.depth_pose_in_colour);
    EXPECT_NE(r.reason.find("not used"), std::string::npos) << r.reason;
  }
  // This recording's depth fits its colour far better read as registered
  // already (2.9 px) than through the Kinect v1's factory extrinsics
  // (4.8 px): the calibrator says so.
  EXPECT_LT(r.distanceRegisteredPx, 0.8 * r.distanceStartPx);
  EXPECT_NE(r.reason.find("as if registered already"), std::string::npos) << r.reason;
}

// The recording reader runs the same estimate when the description asks for
// it, says what it found, and still plays all 12 frames.
TEST(DepthColourCalibrator, RecordingReaderReportsTheEstimate)
{
  const std::string oni = roislam::testing::sharedDataDir() + "/oni/kinect1_room_12frames.oni";
  if (!std::filesystem::is_regular_file(oni))
    GTEST_SKIP() << oni << " not found (shared data absent)";
  auto choice =
      roislam::io::resolveSensor(roislam::testing::sourceDir() + "/config/sensor-kinect1.ini", ".");
  const auto factory = choice.sensor;
  choice.sensor.estimate_registration = true;
  roislam::io::COpenNI2FrameSource source(oni, choice);
  const auto& used = source.sensor();
  EXPECT_NE(used.reason.find("as if registered already"), std::string::npos) << used.reason;
  EXPECT_EQ(used.sensor.depth_pose_in_colour, factory.depth_pose_in_colour);
  std::size_t frames = 0;
  while (auto f = source.next())
  {
    EXPECT_EQ(f->index, frames);
    ++frames;
  }
  EXPECT_EQ(frames, 12u);
}

// Frames without a depth discontinuity (a flat wall): nothing to measure, the
// start stays and the reason says so.
TEST(DepthColourCalibrator, FlatSceneKeepsTheStart)
{
  auto start = roislam::io::sensorPreset("7scenes");
  start.estimate_registration = true;
  CDepthColourCalibrator calibrator(start);
  for (int i = 0; i < 6; ++i)
    calibrator.addFrame(
        cv::Mat(480, 640, CV_8UC3, cv::Scalar(90, 120, 150)),
        cv::Mat(480, 640, CV_32FC1, cv::Scalar(1.5 + 0.1 * i)));
  const auto r = calibrator.estimate();
  EXPECT_FALSE(r.accepted);
  EXPECT_EQ(r.frames, 0u);
  EXPECT_NE(r.reason.find("depth edges"), std::string::npos) << r.reason;
  EXPECT_EQ(r.sensor.depth_pose_in_colour, start.depth_pose_in_colour);
  EXPECT_TRUE(r.sensor.estimate_registration);
}

TEST(DepthColourCalibrator, RejectsWrongInput)
{
  auto registered = roislam::io::sensorPreset("fr1");
  EXPECT_THROW(CDepthColourCalibrator{registered}, std::invalid_argument);
  auto flipped = roislam::io::sensorPreset("7scenes");
  EXPECT_EQ(CDepthColourCalibrator::whyNotEstimable(flipped), "");
  flipped.colour.setIntrinsicParamsFromValues(525, -525, 319.5, 239.5);
  EXPECT_EQ(CDepthColourCalibrator::whyNotEstimable(flipped), "a negative focal length");
  EXPECT_THROW(CDepthColourCalibrator{flipped}, std::invalid_argument);
  CDepthColourCalibrator::TOptions oddTerms;
  oddTerms.distortion_terms = 3;
  EXPECT_THROW(
      CDepthColourCalibrator(roislam::io::sensorPreset("7scenes"), oddTerms),
      std::invalid_argument);
  CDepthColourCalibrator calibrator(roislam::io::sensorPreset("7scenes"));
  EXPECT_THROW(
      calibrator.addFrame(cv::Mat(480, 640, CV_8UC1), cv::Mat(480, 640, CV_32FC1)),
      std::invalid_argument);
  EXPECT_THROW(
      calibrator.addFrame(cv::Mat(480, 640, CV_8UC3), cv::Mat(240, 320, CV_32FC1)),
      std::invalid_argument);
}

// The folder reader estimates when the description asks for it, reads the
// frames with the estimate and says so in the sensor choice's reason.
TEST(DepthColourCalibrator, FolderReaderUsesTheEstimate)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "sevenscenes");
  const auto truth = roislam::io::sensorPreset("7scenes");
  roislam::io::TSensorChoice choice;
  choice.sensor = truth;
  choice.sensor.estimate_registration = true;
  choice.sensor.colour.setIntrinsicParamsFromValues(535, 515, truth.colour.cx(), truth.colour.cy());
  choice.source = "test";
  choice.reason = "a start that is off";
  roislam::io::CTumFrameSource source(seq, choice, roislam::io::CTumFrameSource::TOptions());
  const auto& used = source.sensor();
  EXPECT_NE(used.reason.find("registration estimated"), std::string::npos) << used.reason;
  EXPECT_FALSE(used.sensor.estimate_registration);
  EXPECT_NEAR(used.sensor.colour.fx(), 525, 2.1);
  EXPECT_NEAR(used.sensor.colour.fy(), 525, 2.1);
  EXPECT_DOUBLE_EQ(source.camera().fx(), used.sensor.colour.fx());
  const auto f = source.next();
  ASSERT_TRUE(f);
  EXPECT_DOUBLE_EQ(f->camera.fx(), used.sensor.colour.fx());
}
