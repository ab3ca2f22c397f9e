// The rolling-shutter correction of lifted keypoints (libs/frontend/src
// RollingShutter.h): points observed by a moving rolling-shutter camera, each
// at its own row's time, are carried exactly into the middle row's camera.
// And the depth-time correction: a depth image taken after the colour image
// is read where each point was at the depth's time.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <random>
#include <utility>

#include "KeyframeRegistration.h"
#include "RollingShutter.h"

using roislam::frontend::CRgbdOdometry;
using roislam::frontend::TKeyframe;
using namespace roislam::frontend::detail;

namespace
{
constexpr int kW = 640, kH = 480;
const TPinhole kCam{517.3, 516.5, 318.6, 255.3};

/** Pose of the camera s seconds after the middle row's time, in the middle
 *  row's camera: X_mid = R(omega s) X_s + v s (the model being tested). */
Eigen::Vector3d toMiddle(const TCameraRate& r, double s, const Eigen::Vector3d& Xs)
{
  const Eigen::Vector3d w = r.omega * s;
  const Eigen::Matrix3d R = w.norm() > 0
                                ? Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix()
                                : Eigen::Matrix3d::Identity();
  return R * Xs + r.linear * s;
}

struct TObservation
{
  cv::Point2f pixel;
  Eigen::Vector3d Xs, Xmid;
};

/** Where a rolling-shutter camera sees the point Xmid: the row y whose time
 *  s = (y / H - 0.5) * readout puts the point's image on row y (fixed point). */
TObservation observe(const TCameraRate& r, double readout, const Eigen::Vector3d& Xmid)
{
  double s = 0;
  TObservation o;
  o.Xmid = Xmid;
  for (int it = 0; it < 50; ++it)
  {
    const Eigen::Vector3d w = r.omega * s;
    const Eigen::Matrix3d R = w.norm() > 0
                                  ? Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix()
                                  : Eigen::Matrix3d::Identity();
    o.Xs = R.transpose() * (Xmid - r.linear * s);
    o.pixel = cv::Point2f(
        static_cast<float>(kCam.fx * o.Xs.x() / o.Xs.z() + kCam.cx),
        static_cast<float>(kCam.fy * o.Xs.y() / o.Xs.z() + kCam.cy));
    s = (o.pixel.y / kH - 0.5) * readout;
  }
  return o;
}

struct TScene
{
  roislam::features::TFeatureSet features;
  cv::Mat depth;
  std::vector<TObservation> obs;
};

/** Random points 1-3 m ahead, seen by the moving camera; the depth image
 *  holds each point's depth (at its row's time) at its keypoint's pixel. */
TScene makeScene(const TCameraRate& r, double readout)
{
  TScene sc;
  sc.depth = cv::Mat::zeros(kH, kW, CV_32FC1);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1, 1), Z(1, 3);
  while (sc.obs.size() < 200)
  {
    const double z = Z(rng);
    const Eigen::Vector3d X(U(rng) * 0.5 * z, U(rng) * 0.4 * z, z);
    const TObservation o = observe(r, readout, X);
    const int u = static_cast<int>(std::lround(o.pixel.x)),
              v = static_cast<int>(std::lround(o.pixel.y));
    if (u < 2 || v < 2 || u >= kW - 2 || v >= kH - 2 ||
        cv::countNonZero(sc.depth(cv::Rect(u - 2, v - 2, 5, 5))) != 0)
      continue;
    // The pixel centre's depth is the keypoint's: snap the keypoint to it so
    // the lifted raw point is the observed one exactly.
    const cv::Point2f c(static_cast<float>(u), static_cast<float>(v));
    TObservation snapped = o;
    snapped.Xs = Eigen::Vector3d((u - kCam.cx) / kCam.fx, (v - kCam.cy) / kCam.fy, 1) * o.Xs.z();
    const double s = (v / static_cast<double>(kH) - 0.5) * readout;
    snapped.Xmid = toMiddle(r, s, snapped.Xs);
    snapped.pixel = c;
    // A flat 3x3 neighbourhood, so the depth-edge filter keeps it.
    sc.depth(cv::Rect(u - 1, v - 1, 3, 3)).setTo(static_cast<float>(o.Xs.z()));
    cv::KeyPoint kp(c, 7.f);
    sc.features.keypoints.push_back(kp);
    sc.obs.push_back(snapped);
  }
  sc.features.descriptors = cv::Mat::zeros(static_cast<int>(sc.obs.size()), 32, CV_8U);
  return sc;
}

CRgbdOdometry::TOptions options()
{
  CRgbdOdometry::TOptions o;
  o.min_depth_m = 0.3;
  o.max_depth_m = 5;
  return o;
}

cv::Mat K()
{
  return (cv::Mat_<double>(3, 3) << kCam.fx, 0, kCam.cx, 0, kCam.fy, kCam.cy, 0, 0, 1);
}
}  // namespace

TEST(RollingShutter, CarriesEveryPointIntoTheMiddleRowsCamera)
{
  TCameraRate rate;
  rate.omega = Eigen::Vector3d(0.4, -1.2, 0.3);     // about 75 deg/s
  rate.linear = Eigen::Vector3d(0.15, -0.05, 0.3);  // m/s
  const double readout = 0.02;
  const TScene sc = makeScene(rate, readout);
  TLiftedFeatures lifted =
      liftFeatures(sc.features, sc.depth, K(), cv::Mat::zeros(1, 5, CV_64F), options());
  ASSERT_EQ(lifted.valid.size(), sc.obs.size());
  // Without a correction the points are where the camera saw them.
  for (int i : lifted.valid)
  {
    const auto& o = sc.obs[static_cast<std::size_t>(i)];
    EXPECT_NEAR(lifted.z[static_cast<std::size_t>(i)], o.Xs.z(), 1e-5);
  }
  rectifyRollingShutter(lifted, rate, readout, kCam);
  double worstUncorrected = 0;
  for (int i : lifted.valid)
  {
    const auto k = static_cast<std::size_t>(i);
    const auto& o = sc.obs[k];
    const cv::Point2f& u = lifted.undistorted[k];
    const double z = lifted.z[k];
    const Eigen::Vector3d X((u.x - kCam.cx) / kCam.fx * z, (u.y - kCam.cy) / kCam.fy * z, z);
    EXPECT_LT((X - o.Xmid).norm(), 1e-5) << "keypoint " << i << " at row " << o.pixel.y;
    worstUncorrected = std::max(worstUncorrected, (o.Xs - o.Xmid).norm());
  }
  // The correction mattered: rows far from the middle moved by millimetres
  // to centimetres.
  EXPECT_GT(worstUncorrected, 5e-3);
}

TEST(RollingShutter, ZeroRateOrReadoutRestoresTheRawPoints)
{
  TCameraRate rate;
  rate.omega = Eigen::Vector3d(0, 1.0, 0);
  const TScene sc = makeScene(rate, 0.02);
  TLiftedFeatures lifted =
      liftFeatures(sc.features, sc.depth, K(), cv::Mat::zeros(1, 5, CV_64F), options());
  const auto rawPixels = lifted.undistorted;
  const auto rawZ = lifted.z;
  rectifyRollingShutter(lifted, rate, 0.02, kCam);
  EXPECT_NE(lifted.undistorted, rawPixels);
  rectifyRollingShutter(lifted, TCameraRate{}, 0.02, kCam);
  EXPECT_EQ(lifted.undistorted, rawPixels);
  EXPECT_EQ(lifted.z, rawZ);
  rectifyRollingShutter(lifted, rate, 0.02, kCam);
  rectifyRollingShutter(lifted, rate, 0.0, kCam);
  EXPECT_EQ(lifted.undistorted, rawPixels);
  EXPECT_EQ(lifted.z, rawZ);
}

TEST(RollingShutter, MiddleRowIsNotMoved)
{
  // A keypoint on the middle row was exposed at the frame's time.
  TCameraRate rate;
  rate.omega = Eigen::Vector3d(1.0, 1.0, 1.0);
  rate.linear = Eigen::Vector3d(0.5, 0.5, 0.5);
  roislam::features::TFeatureSet fs;
  fs.keypoints.emplace_back(cv::Point2f(100.f, kH / 2.f), 7.f);
  fs.descriptors = cv::Mat::zeros(1, 32, CV_8U);
  cv::Mat depth(kH, kW, CV_32FC1, cv::Scalar(2.0f));
  TLiftedFeatures lifted = liftFeatures(fs, depth, K(), cv::Mat::zeros(1, 5, CV_64F), options());
  ASSERT_EQ(lifted.valid.size(), 1u);
  rectifyRollingShutter(lifted, rate, 0.03, kCam);
  EXPECT_NEAR(lifted.undistorted[0].x, 100.f, 1e-4);
  EXPECT_NEAR(lifted.undistorted[0].y, kH / 2.f, 1e-4);
  EXPECT_NEAR(lifted.z[0], 2.0, 1e-6);
}

namespace
{
/** A slanted wall n.X = d (colour camera at the colour's time) seen by a depth
 *  image taken dt seconds later, after the camera moved with rate: each depth
 *  pixel holds the wall's depth along its (distorted) pixel's ray in the
 *  depth-time camera. */
struct TLateDepth
{
  Eigen::Vector3d n{0.3, -0.1, 1.0};
  double d = 2.0;
  TCameraRate rate;
  double dt = 0.015;
  cv::Mat K, dist;
  cv::Mat depth;

  /** Depth of the wall along the undistorted pixel u in the colour camera. */
  double colourDepth(const cv::Point2f& u) const
  {
    const Eigen::Vector3d r((u.x - kCam.cx) / kCam.fx, (u.y - kCam.cy) / kCam.fy, 1);
    return d / n.dot(r);
  }

  void render()
  {
    // The depth camera (time dt) in the colour one: X_c = R X_d + t.
    const Eigen::Vector3d w = rate.omega * dt;
    const Eigen::Matrix3d R = w.norm() > 0
                                  ? Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix()
                                  : Eigen::Matrix3d::Identity();
    const Eigen::Vector3d t = rate.linear * dt;
    const Eigen::Vector3d nd = R.transpose() * n;
    const double dd = d - n.dot(t);
    std::vector<cv::Point2f> px, und;
    for (int v = 0; v < kH; ++v)
      for (int u = 0; u < kW; ++u)
        px.emplace_back(static_cast<float>(u), static_cast<float>(v));
    cv::undistortPoints(px, und, K, dist, cv::noArray(), K);
    depth = cv::Mat::zeros(kH, kW, CV_32FC1);
    for (std::size_t i = 0; i < px.size(); ++i)
    {
      const Eigen::Vector3d r((und[i].x - kCam.cx) / kCam.fx, (und[i].y - kCam.cy) / kCam.fy, 1);
      depth.at<float>(static_cast<int>(px[i].y), static_cast<int>(px[i].x)) =
          static_cast<float>(dd / nd.dot(r));
    }
  }
};

/** Keypoints on a grid over the image's inner part. */
roislam::features::TFeatureSet gridKeypoints()
{
  roislam::features::TFeatureSet f;
  for (int v = 60; v < kH - 60; v += 20)
    for (int u = 60; u < kW - 60; u += 20)
      f.keypoints.emplace_back(cv::Point2f(static_cast<float>(u), static_cast<float>(v)), 7.f);
  f.descriptors = cv::Mat::zeros(static_cast<int>(f.keypoints.size()), 32, CV_8U);
  return f;
}

/** Largest |z - the wall's depth at the colour's time| over the valid keypoints. */
double worstDepthError(const TLiftedFeatures& l, const TLateDepth& s)
{
  double worst = 0;
  for (int i : l.valid)
  {
    const auto k = static_cast<std::size_t>(i);
    worst = std::max(worst, std::abs(l.rawZ[k] - s.colourDepth(l.rawUndistorted[k])));
  }
  return worst;
}
}  // namespace

TEST(DepthTime, LateDepthIsReadWhereThePointWasThen)
{
  // Turning at 1 rad/s and moving 0.3 m/s, depth 15 ms late: the depth image
  // is 8 px and 4.5 mm away from the colour image's view.
  const roislam::geometry::TDepthRule rule;
  for (const bool distorted : {false, true})
  {
    SCOPED_TRACE(distorted ? "fr1 distortion" : "no distortion");
    TLateDepth s;
    s.rate.omega = Eigen::Vector3d(0.2, 1.0, 0.1);
    s.rate.linear = Eigen::Vector3d(0.1, 0.0, 0.3);
    s.K = K();
    s.dist = distorted ? (cv::Mat_<double>(1, 5) << 0.2624, -0.9531, -0.0054, 0.0026, 1.1633)
                       : cv::Mat();
    s.render();
    const auto features = gridKeypoints();
    const TLiftedFeatures raw = liftFeatures(features, s.depth, s.K, s.dist, options());
    ASSERT_EQ(raw.valid.size(), features.size());
    TLiftedFeatures aligned = raw;
    alignDepthTime(aligned, s.depth, s.K, s.dist, rule, kCam, s.rate, s.dt, true);
    // Every keypoint keeps a depth (the wall fills the image), the pixels stay.
    EXPECT_GE(aligned.valid.size(), features.size() * 95 / 100);
    for (int i : aligned.valid)
      EXPECT_EQ(
          aligned.rawUndistorted[static_cast<std::size_t>(i)],
          raw.rawUndistorted[static_cast<std::size_t>(i)]);
    const double before = worstDepthError(raw, s), after = worstDepthError(aligned, s);
    // Read at the keypoint's own pixel the depth is centimetres off; read
    // where the point was, within the pixel grid's rounding (~1 mm / px here).
    EXPECT_GT(before, 0.01);
    EXPECT_LT(after, 0.002) << "before " << before;
    // Aligned again (a refined rate) it starts from the depth as read, not
    // from the last alignment, and keeps the valid set: a wrong rate first,
    // then the right one, ends where the right one alone does.
    TLiftedFeatures again = aligned;
    TCameraRate wrong;
    wrong.omega = -s.rate.omega;
    alignDepthTime(again, s.depth, s.K, s.dist, rule, kCam, wrong, s.dt, false);
    EXPECT_EQ(again.valid, aligned.valid);
    EXPECT_GT(worstDepthError(again, s), 0.01);
    alignDepthTime(again, s.depth, s.K, s.dist, rule, kCam, s.rate, s.dt, false);
    EXPECT_EQ(again.valid, aligned.valid);
    EXPECT_LT(worstDepthError(again, s), 0.002);
  }
}

TEST(DepthTime, NoOffsetOrNoMotionChangesNothing)
{
  TLateDepth s;
  s.rate.omega = Eigen::Vector3d(0, 1.0, 0);
  s.K = K();
  s.render();
  const auto features = gridKeypoints();
  const TLiftedFeatures raw = liftFeatures(features, s.depth, s.K, s.dist, options());
  for (const auto& [rate, dt] : {std::pair{s.rate, 0.0}, std::pair{TCameraRate{}, 0.015}})
  {
    TLiftedFeatures l = raw;
    alignDepthTime(l, s.depth, s.K, s.dist, roislam::geometry::TDepthRule{}, kCam, rate, dt, true);
    EXPECT_EQ(l.valid, raw.valid);
    EXPECT_EQ(l.rawZ, raw.rawZ);
  }
}

// Keypoint timing noise (KeyframeRegistration.h motionSigmaPx): a keypoint
// whose time is uncertain by tau is uncertain in the image by its image
// speed times tau, from the velocity its frame was lifted with.
namespace
{
/** Where the point X (in the camera at time 0) is seen t seconds later by a
 *  camera turning at omega and moving at v (its own frame). */
cv::Point2d seenAt(const TCameraRate& r, double t, const Eigen::Vector3d& X)
{
  const Eigen::Vector3d w = r.omega * t;
  const Eigen::Matrix3d R = w.norm() > 0
                                ? Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix()
                                : Eigen::Matrix3d::Identity();
  const Eigen::Vector3d Xt = R.transpose() * (X - r.linear * t);
  return {kCam.fx * Xt.x() / Xt.z() + kCam.cx, kCam.fy * Xt.y() / Xt.z() + kCam.cy};
}

mrpt::math::TVector3D toMrpt3(const Eigen::Vector3d& v)
{
  return {v.x(), v.y(), v.z()};
}
}  // namespace

TEST(KeypointTiming, SigmaIsTheImageSpeedTimesTheTime)
{
  TCameraRate rate;
  rate.omega = Eigen::Vector3d(0.3, 1.0, -0.2);   // about 60 deg/s
  rate.linear = Eigen::Vector3d(0.2, -0.1, 0.3);  // m/s
  const double tau = 0.0015;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-1, 1), Z(0.8, 4);
  for (int i = 0; i < 50; ++i)
  {
    const double z = Z(rng);
    const Eigen::Vector3d X(U(rng) * 0.5 * z, U(rng) * 0.4 * z, z);
    // The image speed by central differences of the exact motion.
    constexpr double h = 1e-5;
    const double speed = cv::norm(seenAt(rate, h, X) - seenAt(rate, -h, X)) / (2 * h);
    const double sigma =
        motionSigmaPx({X.x(), X.y(), X.z()}, toMrpt3(rate.omega), toMrpt3(rate.linear), kCam, tau);
    EXPECT_GT(sigma, 0.1) << "a fast turn moves keypoints by hundreds of px/s";
    EXPECT_NEAR(sigma, speed * tau, 1e-3 * speed * tau) << "point " << i;
  }
  // No time, no motion, or a point behind the camera: nothing.
  const mrpt::math::TPoint3D X(0.2, -0.1, 2.0);
  EXPECT_EQ(motionSigmaPx(X, toMrpt3(rate.omega), toMrpt3(rate.linear), kCam, 0), 0);
  EXPECT_EQ(motionSigmaPx(X, {0, 0, 0}, {0, 0, 0}, kCam, tau), 0);
  EXPECT_EQ(
      motionSigmaPx({0.2, -0.1, -2.0}, toMrpt3(rate.omega), toMrpt3(rate.linear), kCam, tau), 0);
}

TEST(KeypointTiming, FeatureSetsCarryTheRateTheirPointsWereCorrectedWith)
{
  TCameraRate rate;
  rate.omega = Eigen::Vector3d(0.4, -1.2, 0.3);
  rate.linear = Eigen::Vector3d(0.15, -0.05, 0.3);
  const TScene sc = makeScene(rate, 0.02);
  TLiftedFeatures lifted =
      liftFeatures(sc.features, sc.depth, K(), cv::Mat::zeros(1, 5, CV_64F), options());
  // A global shutter (readout 0) records the rate too: the term needs no
  // readout.
  rectifyRollingShutter(lifted, rate, 0, kCam);
  TKeyframe k = makeFeatureSet(sc.features, lifted, lifted.valid, kCam);
  EXPECT_NEAR(k.angularRate.y, -1.2, 1e-12);
  EXPECT_NEAR(k.linearRate.z, 0.3, 1e-12);
  // A new correction with another rate replaces it.
  rectifyRollingShutter(lifted, TCameraRate{}, 0.02, kCam);
  updateFeatureSetPoints(k, lifted, lifted.valid, kCam);
  EXPECT_EQ(k.angularRate.norm(), 0);
  EXPECT_EQ(k.linearRate.norm(), 0);
}

TEST(KeypointTiming, WidensTheNoiseOfAnEdgeSeenWhileTurning)
{
  // The same points seen twice from one place: a registration whose
  // information falls, with the timing noise, as fast as the frame turns.
  TKeyframe ref;
  ref.features.type = roislam::features::EFeatureType::ORB;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(-1, 1), Z(1, 3);
  std::normal_distribution<double> N(0, 0.7);
  TKeyframe cur = ref;
  TRegistration r;
  for (int i = 0; i < 120; ++i)
  {
    const double z = Z(rng);
    const Eigen::Vector3d X(U(rng) * 0.5 * z, U(rng) * 0.4 * z, z);
    const cv::Point2f u = kCam.project(X);
    for (TKeyframe* k : {&ref, &cur})
    {
      k->features.keypoints.emplace_back(u, 31.f);
      k->points.emplace_back(X.x(), X.y(), X.z());
      k->pixels.push_back(
          k == &ref
              ? u
              : cv::Point2f(u.x + static_cast<float>(N(rng)), u.y + static_cast<float>(N(rng))));
    }
    r.pairs.emplace_back(i, i);
    r.inlierPairs.push_back(static_cast<std::size_t>(i));
  }
  ref.features.descriptors = cv::Mat::zeros(120, 32, CV_8U);
  cur.features.descriptors = ref.features.descriptors.clone();
  CRgbdOdometry::TOptions o = options();
  o.reprojection_threshold_px = 50;  // every pair an inlier, whatever its sigma
  const auto still = refineRegistration(ref, cur, r, kCam, o);
  ASSERT_TRUE(still);
  // With a timing noise but no motion, nothing changes.
  o.keypoint_time_sigma_ms = 5;
  const auto noMotion = refineRegistration(ref, cur, r, kCam, o);
  ASSERT_TRUE(noMotion);
  EXPECT_NEAR(
      noMotion->edgeInformation.trace(), still->edgeInformation.trace(),
      1e-9 * still->edgeInformation.trace());
  // The current frame turning at 60 deg/s: its keypoints move about 540 px/s,
  // 2.7 px in 5 ms, so the information falls several fold.
  cur.angularRate = {0, 1.05, 0};
  const auto turning = refineRegistration(ref, cur, r, kCam, o);
  ASSERT_TRUE(turning);
  EXPECT_LT(turning->edgeInformation.trace(), 0.5 * still->edgeInformation.trace());
  EXPECT_GT(turning->edgeInformation.trace(), 0.01 * still->edgeInformation.trace());
}
