// geometry::liftPixels, the project's one depth rule: the reading at the
// rounded pixel within the range, none on a depth edge, hole or image border,
// rays through the undistorted pixel; TPinhole's projections.
#include <gtest/gtest.h>
#include <roislam/geometry/KeypointLifting.h>

#include <opencv2/calib3d.hpp>

using namespace roislam::geometry;

namespace
{
const TPinhole kPinhole{525.0, 520.0, 319.5, 239.5};

cv::Mat K()
{
  return (
      cv::Mat_<double>(3, 3) << kPinhole.fx, 0, kPinhole.cx, 0, kPinhole.fy, kPinhole.cy, 0, 0, 1);
}
}  // namespace

TEST(KeypointLifting, DepthRule)
{
  cv::Mat depth(480, 640, CV_32FC1, cv::Scalar(2.0f));
  depth(cv::Rect(300, 0, 340, 480)).setTo(2.5f);  // a step at u = 300
  depth.at<float>(100, 51) = 0;                   // a hole beside (50, 100)
  depth.at<float>(400, 100) = 9.0f;               // out of range
  const std::vector<cv::Point2f> px{
      {100.4f, 200.4f},  // 0: plain, 2 m
      {299.6f, 200.f},   // 1: rounds to u = 300, on the step
      {50.f, 100.f},     // 2: beside a hole
      {100.f, 400.f},    // 3: 9 m
      {0.f, 10.f},       // 4: border column
      {500.f, 300.f}};   // 5: plain, 2.5 m
  TDepthRule rule;
  rule.min_depth_m = 0.3;
  rule.max_depth_m = 4.0;
  rule.depth_discontinuity_m = 0.05;
  const auto l = liftPixels(px, depth, K(), cv::noArray(), rule);
  EXPECT_EQ(l.valid, (std::vector<int>{0, 5}));
  ASSERT_EQ(l.z.size(), px.size());
  EXPECT_FLOAT_EQ(l.z[0], 2.0f);
  EXPECT_FLOAT_EQ(l.z[5], 2.5f);
  EXPECT_EQ(l.z[1], 0.0f);
  // Without the edge test the step and the hole's neighbour have depth.
  rule.depth_discontinuity_m = 0;
  EXPECT_EQ(liftPixels(px, depth, K(), cv::noArray(), rule).valid, (std::vector<int>{0, 1, 2, 5}));
  EXPECT_THROW(liftPixels(px, cv::Mat(480, 640, CV_16UC1), K(), {}, rule), std::invalid_argument);
  EXPECT_TRUE(liftPixels({}, depth, K(), {}, rule).valid.empty());
}

TEST(KeypointLifting, RaysThroughTheUndistortedPixel)
{
  // A point seen through a distorting lens: its distorted pixel carries the
  // depth, its undistorted pixel the ray, and back-projection recovers it.
  const cv::Mat dist = (cv::Mat_<double>(1, 5) << 0.26, -0.95, -0.005, 0.003, 1.16);
  const Eigen::Vector3d X(0.6, -0.4, 1.5);
  const std::vector<cv::Point3f> obj{cv::Point3f(0.6f, -0.4f, 1.5f)};
  std::vector<cv::Point2f> img;
  cv::projectPoints(obj, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K(), dist, img);
  const cv::Mat depth(480, 640, CV_32FC1, cv::Scalar(1.5f));
  const auto l = liftPixels(img, depth, K(), dist, TDepthRule());
  ASSERT_EQ(l.valid.size(), 1u);
  EXPECT_LT((kPinhole.backProject(l.undistorted[0], l.z[0]) - X).norm(), 1e-4);
  const cv::Point2f u = kPinhole.project(X);
  EXPECT_NEAR(u.x, l.undistorted[0].x, 0.05);
  EXPECT_NEAR(u.y, l.undistorted[0].y, 0.05);
  // The lens moves this point by pixels: the distorted pixel's ray is wrong.
  EXPECT_GT(cv::norm(img[0] - u), 5.0);
}
