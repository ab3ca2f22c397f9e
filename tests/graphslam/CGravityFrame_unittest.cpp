/* CGravityFrame: which way is up in a run's pictures. Synthetic cameras with
 * a known world (z up): the estimate's world is the first camera's optical
 * frame, as roi-graphslam's is; the accelerometer reads the specific force
 * in the Kinect's axes, with motion and noise. */
#include <gtest/gtest.h>
#include <mrpt/random/RandomGenerators.h>
#include <roislam/graphslam/CGravityFrame.h>
#include <roislam/testing/TestData.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

using mrpt::math::TVector3D;
using mrpt::poses::CPose3D;
using roislam::graphslam::CGravityFrame;

namespace
{
// Body (x forward, y left, z up) to optical (x right, y down, z forward).
const CPose3D kBodyToOptical(0, 0, 0, -M_PI / 2, 0, -M_PI / 2);

/** True camera poses in a z-up world: a hand-held wobble around a desk. */
std::vector<CPose3D> trueCameras(std::size_t n)
{
  std::vector<CPose3D> cams;
  for (std::size_t i = 0; i < n; ++i)
  {
    const double s = static_cast<double>(i) / n * 2 * M_PI;
    cams.push_back(
        CPose3D(
            0.3 * std::sin(s), 0.2 * std::cos(s), 1.4, 0.4 + 0.3 * std::sin(s),
            mrpt::DEG2RAD(25.0) + 0.1 * std::sin(2 * s), mrpt::DEG2RAD(7.0)) +
        kBodyToOptical);
  }
  return cams;
}

/** The estimate as roi-graphslam has it: in the first camera's frame. */
roislam::io::TTrajectory estimateOf(const std::vector<CPose3D>& cams)
{
  roislam::io::TTrajectory t;
  for (std::size_t i = 0; i < cams.size(); ++i)
    t.push_back({100.0 + i / 30.0, cams[i] - cams[0]});
  return t;
}

/** Specific force (gravity + random motion accelerations, zero mean) in the
 *  Kinect's axes, 3 samples per frame. */
roislam::io::TAccelerometerLog accelerometerOf(
    const std::vector<CPose3D>& cams, double motionStd, double noiseStd)
{
  mrpt::random::CRandomGenerator rng(7);
  roislam::io::TAccelerometerLog log;
  for (std::size_t i = 0; i < cams.size(); ++i)
    for (int k = 0; k < 3; ++k)
    {
      const TVector3D motion(
          rng.drawGaussian1D(0, motionStd), rng.drawGaussian1D(0, motionStd),
          rng.drawGaussian1D(0, motionStd));
      const TVector3D optical = cams[i].inverseRotateVector(motion + TVector3D(0, 0, 9.81));
      // The Kinect's axes: the optical ones turned half a turn about z.
      TVector3D kinect(-optical.x, -optical.y, optical.z);
      kinect = kinect + TVector3D(
                            rng.drawGaussian1D(0, noiseStd), rng.drawGaussian1D(0, noiseStd),
                            rng.drawGaussian1D(0, noiseStd));
      log.push_back({100.0 + i / 30.0 + (k - 1) * 0.01, kinect});
    }
  return log;
}

double angleDeg(const TVector3D& a, const TVector3D& b)
{
  const double c = (a.x * b.x + a.y * b.y + a.z * b.z) / (a.norm() * b.norm());
  return mrpt::RAD2DEG(std::acos(std::clamp(c, -1.0, 1.0)));
}

/** Where the true world's up lands in the display frame. */
TVector3D displayedUp(const CGravityFrame::TResult& r, const CPose3D& firstCamera)
{
  const TVector3D upInEstimate = firstCamera.inverseRotateVector(TVector3D(0, 0, 1));
  return r.toDisplay.rotateVector(upInEstimate);
}
}  // namespace

TEST(GravityFrame, AccelerometerLevelsTheMapDespiteMotionAndNoise)
{
  const auto cams = trueCameras(150);
  const auto est = estimateOf(cams);
  const auto r = CGravityFrame::choose(est, std::nullopt, accelerometerOf(cams, 1.5, 0.1));
  ASSERT_EQ(r.source, CGravityFrame::ESource::Accelerometer) << r.note;
  EXPECT_EQ(r.accelerometerSamples, 450u);
  EXPECT_LT(angleDeg(displayedUp(r, cams[0]), TVector3D(0, 0, 1)), 1.0);
  // Origin at the first camera, its view levelled along +y.
  const auto origin = r.toDisplay.composePoint(mrpt::math::TPoint3D(0, 0, 0));
  EXPECT_LT(origin.norm(), 1e-9);
  const TVector3D view = r.toDisplay.rotateVector(TVector3D(0, 0, 1));
  EXPECT_GT(view.y, 0.85);
  EXPECT_NEAR(view.x, 0, 0.03);
  EXPECT_EQ(r.toJson()["up"], "accelerometer");
}

// The real TUM accelerometer against the motion capture: levelling with it
// (our estimate replaced by the ground truth's rotations, in the first
// camera's frame) puts the ground truth's z up within a few degrees.
TEST(GravityFrame, TumAccelerometerAgreesWithTheGroundTruth)
{
  bool any = false;
  for (const char* name :
       {"rgbd_dataset_freiburg1_xyz_first150", "rgbd_dataset_freiburg1_rpy_first250"})
  {
    const std::string dir = roislam::testing::sharedDataDir() + "/tum/" + name;
    if (!std::filesystem::exists(dir + "/accelerometer.txt"))
      continue;
    any = true;
    const auto gt = roislam::io::loadTumTrajectory(dir + "/groundtruth.txt");
    std::vector<CPose3D> cams;
    for (const auto& p : gt)
      cams.push_back(p.pose);
    roislam::io::TTrajectory est;
    for (const auto& p : gt)
      est.push_back({p.timestamp, p.pose - gt.front().pose});
    const auto r = CGravityFrame::choose(
        est, std::nullopt, std::optional<std::string>(dir + "/accelerometer.txt"));
    ASSERT_EQ(r.source, CGravityFrame::ESource::Accelerometer) << name << ": " << r.note;
    EXPECT_GT(r.accelerometerSamples, 1000u) << name;
    const double err = angleDeg(displayedUp(r, cams[0]), TVector3D(0, 0, 1));
    EXPECT_LT(err, 6.0) << name;
    std::printf(
        "%s: accelerometer up vs ground truth z: %.2f deg (%zu samples)\n", name, err,
        r.accelerometerSamples);
  }
  if (!any)
    GTEST_SKIP() << "shared TUM data not found under " << roislam::testing::sharedDataDir();
}

TEST(GravityFrame, GroundTruthAlignmentWinsAndIsComparedWithTheAccelerometer)
{
  const auto cams = trueCameras(60);
  const auto est = estimateOf(cams);
  // The ATE alignment maps the estimate onto the ground truth: here cams[0].
  const auto r = CGravityFrame::choose(est, cams[0], accelerometerOf(cams, 0.5, 0.05));
  ASSERT_EQ(r.source, CGravityFrame::ESource::GroundTruth);
  EXPECT_LT((r.toDisplay.asVectorVal() - cams[0].asVectorVal()).norm(), 1e-12);
  ASSERT_TRUE(r.accelerometerVsGroundTruthDeg);
  EXPECT_LT(*r.accelerometerVsGroundTruthDeg, 1.0);
  const auto j = r.toJson();
  EXPECT_EQ(j["up"], "ground_truth");
  EXPECT_TRUE(j.contains("accelerometer_vs_ground_truth_deg"));
  EXPECT_NEAR(j["estimate_to_display"]["z"].get<double>(), 1.4, 1e-9);
}

TEST(GravityFrame, FirstCameraFallbackPutsItsMinusYUp)
{
  const auto cams = trueCameras(30);
  const auto est = estimateOf(cams);
  const auto r = CGravityFrame::choose(est, std::nullopt, roislam::io::TAccelerometerLog{});
  ASSERT_EQ(r.source, CGravityFrame::ESource::FirstCamera);
  EXPECT_TRUE(r.note.empty()) << r.note;
  const TVector3D up = r.toDisplay.rotateVector(TVector3D(0, -1, 0));
  EXPECT_LT(angleDeg(up, TVector3D(0, 0, 1)), 1e-6);
  const TVector3D view = r.toDisplay.rotateVector(TVector3D(0, 0, 1));
  EXPECT_LT(angleDeg(view, TVector3D(0, 1, 0)), 1e-6);
  // The camera was pitched 25 deg down: this fallback is that far off.
  EXPECT_NEAR(angleDeg(displayedUp(r, cams[0]), TVector3D(0, 0, 1)), 26.0, 1.5);
}

TEST(GravityFrame, RefusesTooFewOrDisagreeingSamples)
{
  const auto cams = trueCameras(60);
  const auto est = estimateOf(cams);
  auto few = accelerometerOf(cams, 0.1, 0.01);
  few.resize(CGravityFrame::kMinSamples - 1);
  auto r = CGravityFrame::choose(est, std::nullopt, few);
  EXPECT_EQ(r.source, CGravityFrame::ESource::FirstCamera);
  EXPECT_NE(r.note.find("samples"), std::string::npos) << r.note;

  // Samples far from every frame's stamp do not count.
  auto late = accelerometerOf(cams, 0.1, 0.01);
  for (auto& s : late)
    s.timestamp += 100;
  r = CGravityFrame::choose(est, std::nullopt, late);
  EXPECT_EQ(r.source, CGravityFrame::ESource::FirstCamera);

  // Readings pointing every which way (wrong axes, broken sensor).
  roislam::io::TAccelerometerLog random;
  mrpt::random::CRandomGenerator rng(3);
  for (std::size_t i = 0; i < est.size(); ++i)
    random.push_back(
        {est[i].timestamp,
         TVector3D(rng.drawGaussian1D(0, 9), rng.drawGaussian1D(0, 9), rng.drawGaussian1D(0, 9))});
  r = CGravityFrame::choose(est, std::nullopt, random);
  EXPECT_EQ(r.source, CGravityFrame::ESource::FirstCamera);
  EXPECT_NE(r.note.find("disagree"), std::string::npos) << r.note;
}

TEST(GravityFrame, UnreadableAccelerometerFileFallsBackWithItsError)
{
  const auto cams = trueCameras(30);
  const auto est = estimateOf(cams);
  const std::string dir = roislam::testing::makeTempDir("gravity_frame");
  const std::string file = dir + "/accelerometer.txt";
  std::ofstream(file) << "# timestamp ax ay az\n100.0 0 9.8 0\n100.1 0 9.8\n";
  auto r = CGravityFrame::choose(est, std::nullopt, std::optional<std::string>(file));
  EXPECT_EQ(r.source, CGravityFrame::ESource::FirstCamera);
  EXPECT_NE(r.note.find(file + ":3:"), std::string::npos) << r.note;
  r = CGravityFrame::choose(est, std::nullopt, std::optional<std::string>(dir + "/missing.txt"));
  EXPECT_EQ(r.source, CGravityFrame::ESource::FirstCamera);
  EXPECT_NE(r.note.find("missing.txt: cannot open"), std::string::npos) << r.note;
  std::filesystem::remove_all(dir);
}
