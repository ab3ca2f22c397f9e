// The rolling-shutter correction of lifted keypoints (libs/frontend/src
// RollingShutter.h): points observed by a moving rolling-shutter camera, each
// at its own row's time, are carried exactly into the middle row's camera.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <opencv2/core.hpp>
#include <random>

#include "RollingShutter.h"

using roislam::frontend::CRgbdOdometry;
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
