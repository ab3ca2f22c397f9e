/* CObservationProcessor and FeatureGeometry: a landmark at a known 3-D
 * position gives MRPT's range/yaw/pitch; feature depths and positions from a
 * depth image; regions with extracted features (the SLAM back end's path). */
#include <gtest/gtest.h>
#include <mrpt/core/bits_math.h>
#include <roislam/io/ObservationConversion.h>
#include <roislam/landmarks/CObservationProcessor.h>
#include <roislam/landmarks/FeatureGeometry.h>

#include <cmath>
#include <limits>

#include "SyntheticScene.h"

using namespace roislam;
using namespace roislam::landmarks;

TEST(ObservationProcessor, KnownPositionsGiveMrptBearingRange)
{
  TObservationOptions o;
  const auto obs = CObservationProcessor::makeObservation(
      {{3, {1.0, 0.0, 2.0}}, {5, {0.0, -1.0, 2.0}}, {8, {0.0, 0.0, 4.0}}}, test::testCamera(), 12.5,
      mrpt::poses::CPose3D(), o);
  ASSERT_EQ(obs->sensedData.size(), 3u);
  const double r5 = std::sqrt(5.0);

  // Optical +x (image right) is MRPT -y: a negative yaw, no pitch.
  const auto& a = obs->sensedData[0];
  EXPECT_EQ(a.landmarkID, 3);
  EXPECT_NEAR(a.range, r5, 1e-5);
  EXPECT_NEAR(a.yaw, std::atan2(-1.0, 2.0), 1e-5);
  EXPECT_NEAR(a.pitch, 0.0, 1e-6);

  // Optical -y (image up) is MRPT +z: negative pitch (MRPT pitch is positive downwards).
  const auto& b = obs->sensedData[1];
  EXPECT_EQ(b.landmarkID, 5);
  EXPECT_NEAR(b.range, r5, 1e-5);
  EXPECT_NEAR(b.yaw, 0.0, 1e-6);
  EXPECT_NEAR(b.pitch, -std::asin(1.0 / r5), 1e-5);

  // Straight ahead.
  EXPECT_NEAR(obs->sensedData[2].range, 4.0, 1e-6);
  EXPECT_NEAR(obs->sensedData[2].yaw, 0.0, 1e-6);
  EXPECT_NEAR(obs->sensedData[2].pitch, 0.0, 1e-6);

  // Sensor description.
  EXPECT_EQ(obs->sensorLabel, "ROI_LANDMARKS");
  // Each measurement carries the depth-noise model's covariance.
  EXPECT_TRUE(obs->validCovariances);
  const double far = 0.02 * 0.02 + std::pow(1.425e-3 * 16, 2);  // the point at 4 m depth
  EXPECT_NEAR(obs->sensedData[2].covariance(0, 0), far, 1e-9);
  EXPECT_NEAR(obs->sensedData[0].covariance(1, 1), 0.01 * 0.01, 1e-12);
  EXPECT_NEAR(obs->sensedData[0].covariance(2, 2), 0.01 * 0.01, 1e-12);
  EXPECT_NEAR(obs->fieldOfView_yaw, 2 * std::atan(320.0 / 525.0), 1e-5);
  EXPECT_NEAR(obs->fieldOfView_pitch, 2 * std::atan(240.0 / 525.0), 1e-5);
  EXPECT_FLOAT_EQ(obs->maxSensorDistance, 8.0f);
  EXPECT_FLOAT_EQ(obs->sensor_std_range, 0.02f);
  EXPECT_NEAR(mrpt::Clock::toDouble(obs->timestamp), 12.5, 1e-6);
}

TEST(ObservationProcessor, MeasurementsReconstructThePointThroughTheSensorPose)
{
  // Robot frame = optical camera frame (TUM poses): the sensor pose on the
  // robot is mrptCameraInOptical(); composing the spherical measurement with
  // it must give the optical point back, in the world too.
  const mrpt::poses::CPose3D sensorPose = mrptCameraInOptical();
  const mrpt::poses::CPose3D robotPose(1.0, -2.0, 0.5, 0.3, -0.2, 0.1);
  for (const mrpt::math::TPoint3D p : {mrpt::math::TPoint3D(0.3, -0.4, 1.7), {-1.0, 0.5, 3.0}})
  {
    const auto obs = CObservationProcessor::makeObservation(
        {{0, p}}, test::testCamera(), 0, sensorPose, TObservationOptions());
    const auto& m = obs->sensedData.at(0);
    const mrpt::poses::CPose3D dir(0, 0, 0, m.yaw, m.pitch, 0);
    const auto local = dir.composePoint(mrpt::math::TPoint3D(m.range, 0, 0));
    const auto inRobot = obs->sensorLocationOnRobot.composePoint(local);
    EXPECT_NEAR(inRobot.x, p.x, 1e-5);
    EXPECT_NEAR(inRobot.y, p.y, 1e-5);
    EXPECT_NEAR(inRobot.z, p.z, 1e-5);
    // And MRPT's own sphericalCoordinates from the sensor's world pose agrees.
    double range, yaw, pitch;
    (robotPose + sensorPose).sphericalCoordinates(robotPose.composePoint(p), range, yaw, pitch);
    EXPECT_NEAR(range, m.range, 1e-5);
    EXPECT_NEAR(yaw, m.yaw, 1e-5);
    EXPECT_NEAR(pitch, m.pitch, 1e-5);
  }
}

TEST(FeatureGeometry, DepthStatisticsAndPositionOnAPlane)
{
  const auto cam = test::testCamera();
  cv::Mat depth(480, 640, CV_32FC1, cv::Scalar(2.0f));
  depth(cv::Rect(0, 0, 320, 480)).setTo(1.0f);  // left half nearer
  std::vector<cv::KeyPoint> kps;
  for (int i = 0; i < 5; ++i)
    kps.emplace_back(cv::Point2f(400 + 10 * i, 300), 5.f);
  kps.emplace_back(cv::Point2f(100, 100), 5.f);  // left half, 1 m
  kps.emplace_back(cv::Point2f(-5, 100), 5.f);   // outside the image: ignored
  depth.at<float>(301, 600) = 0;                 // no reading: no depth (the
  kps.emplace_back(cv::Point2f(600, 301), 5.f);  // neighbours' is not borrowed)
  depth.at<float>(200, 501) = 0;                 // a hole beside a keypoint...
  kps.emplace_back(cv::Point2f(500, 200), 5.f);  // ...does not matter (no edge test)
  const auto d = featureDepth(kps, depth, cam, 0.1, 8.0);
  EXPECT_EQ(d.valid, 7);
  EXPECT_NEAR(d.mean, (6 * 2.0 + 1.0) / 7, 1e-6);
  EXPECT_NEAR(d.median, 2.0, 1e-6);
  ASSERT_TRUE(d.position);
  // Median x over u = 400..440 (2 m), 500 (2 m), 100 (1 m): u = 420 at 2 m.
  EXPECT_NEAR(d.position->x, (420 - cam.cx()) * 2.0 / cam.fx(), 1e-3);
  EXPECT_NEAR(d.position->y, (300 - cam.cy()) * 2.0 / cam.fy(), 1e-3);
  EXPECT_NEAR(d.position->z, 2.0, 1e-6);

  // Out-of-range depths are ignored; nothing valid gives NaN and no position.
  const auto none = featureDepth(kps, depth, cam, 3.0, 8.0);
  EXPECT_EQ(none.valid, 0);
  EXPECT_TRUE(std::isnan(none.mean));
  EXPECT_FALSE(none.position);
}

TEST(FeatureGeometry, RigidFitRecoversAMotionDespiteOutliers)
{
  const mrpt::poses::CPose3D motion(0.1, -0.05, 0.2, 0.3, -0.1, 0.05);
  std::vector<mrpt::math::TPoint3D> before, after;
  for (int i = 0; i < 40; ++i)
  {
    const mrpt::math::TPoint3D p(0.05 * (i % 7) - 0.15, 0.04 * (i % 5) - 0.1, 1.0 + 0.03 * (i % 9));
    before.push_back(p);
    after.push_back(motion.composePoint(p));
  }
  for (int i = 0; i < 40; i += 5)
    after[i].z += 0.5;  // 8 outliers (depth edges, say)
  const double nan = std::numeric_limits<double>::quiet_NaN();
  before[1] = {nan, nan, nan};  // no depth: ignored
  const auto fit = fitRigid(after, before, 0.01);
  ASSERT_TRUE(fit);
  EXPECT_EQ(fit->pairs, 39);
  EXPECT_EQ(fit->inliers, 31);
  EXPECT_LT(fit->rms, 1e-6);
  EXPECT_NEAR(fit->pose.x(), 0.1, 1e-6);
  EXPECT_NEAR(fit->pose.yaw(), 0.3, 1e-6);
  EXPECT_FALSE(fitRigid({{0, 0, 1}, {1, 0, 1}}, {{0, 0, 1}, {1, 0, 1}}, 0.01));
}

TEST(FeatureGeometry, OpticalToMrptCamera)
{
  const auto q = opticalToMrptCamera({1, 2, 3});
  EXPECT_EQ(q, mrpt::math::TPoint3D(3, -1, -2));
  const auto back = mrptCameraInOptical().composePoint(q);
  EXPECT_NEAR(back.x, 1, 1e-9);
  EXPECT_NEAR(back.y, 2, 1e-9);
  EXPECT_NEAR(back.z, 3, 1e-9);
}

TEST(ObservationProcessor, RegionsWithExtractedFeaturesAreIdentified)
{
  // The SLAM back end's path: a keyframe's ROI with its features already
  // extracted, no confirmation. The first is stored, a warped view of it is
  // recalled; without depth points neither has a position, so the
  // observations carry no measurement.
  const cv::Mat base = test::onCanvas(test::texturePatch(3), {200, 150});
  const features::CFeatureExtractor extractor;
  CObservationProcessor proc;
  std::vector<CObservationProcessor::TOutput> outs;
  for (int i = 0; i < 2; ++i)
  {
    TRegion region;
    region.frame = 10 + i;
    region.timestamp = 1.0 + i;
    region.box = cv::Rect(180, 130, 280, 220);
    region.imageSize = base.size();
    region.features =
        extractor.extract(test::warped(base, 3.0 * i, {5.f * i, 2.f * i})).subset(region.box);
    outs.push_back(proc.processRegion(region));
  }
  ASSERT_EQ(outs[0].result.status, ERoiStatus::Landmark);
  EXPECT_TRUE(outs[0].result.newLandmark);
  ASSERT_EQ(outs[1].result.status, ERoiStatus::Landmark);
  EXPECT_FALSE(outs[1].result.newLandmark);
  EXPECT_EQ(outs[1].result.landmarkId, outs[0].result.landmarkId);
  EXPECT_GT(outs[1].result.recallInliers, 10);
  for (const auto& o : outs)
    EXPECT_TRUE(o.observation->sensedData.empty());
  ASSERT_EQ(proc.tracker().database().size(), 1u);
  EXPECT_EQ(proc.tracker().database().landmark(0).sightings.size(), 2u);
  EXPECT_EQ(proc.tracker().database().landmark(0).sightings[1].frame, 11u);
}

TEST(ObservationProcessor, ProcessesFramesEndToEnd)
{
  // A textured patch seen in three frames: the second confirms it (new
  // landmark 0) and the third recalls it; each gives one measurement.
  const cv::Mat base = test::onCanvas(test::texturePatch(3), {200, 150});
  CObservationProcessor proc;
  std::vector<CObservationProcessor::TOutput> outs;
  for (int i = 0; i < 3; ++i)
    outs.push_back(
        proc.process(test::makeFrame(i, test::warped(base, 2.0 * i, {6.f * i, 3.f * i}))));
  EXPECT_EQ(outs[0].result.status, ERoiStatus::NotConfirmed);
  EXPECT_TRUE(outs[0].observation->sensedData.empty());
  for (int i : {1, 2})
  {
    ASSERT_EQ(outs[i].result.status, ERoiStatus::Landmark) << i;
    EXPECT_EQ(outs[i].result.landmarkId, 0);
    ASSERT_EQ(outs[i].observation->sensedData.size(), 1u);
    const auto& m = outs[i].observation->sensedData[0];
    EXPECT_EQ(m.landmarkID, 0);
    // On a plane at 1.5 m, a point near the image centre is at >= 1.5 m.
    EXPECT_GE(m.range, 1.5f - 1e-4f);
    EXPECT_LT(m.range, 1.7f);
  }
  EXPECT_TRUE(outs[1].result.newLandmark);
  EXPECT_FALSE(outs[2].result.newLandmark);

  // An MRPT scan goes through the one conversion to a frame
  // (io::observationToFrame); observations carry [ObservationProcessor]
  // sensor_pose, by default the optical-frame robot of our rawlogs.
  const auto f = test::makeFrame(3, test::warped(base, 5.0, {15.f, 8.f}));
  const auto scan = io::frameToObservation(f);
  auto frame = io::observationToFrame(*scan, "test scan");
  frame.index = 3;
  const auto out = proc.process(frame);
  ASSERT_EQ(out.result.status, ERoiStatus::Landmark);
  EXPECT_EQ(out.result.landmarkId, 0);
  EXPECT_EQ(out.observation->sensorLocationOnRobot, io::tumSensorPose());
}
