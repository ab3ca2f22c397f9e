// The optical flow of keyframe anchors (libs/frontend/src FlowTracking.h): a
// textured plane seen by a pinhole camera, then by the camera moved; the
// anchors found on the first image, started where the predicted motion puts
// them, land where the true motion projects them, also when the prediction
// is off by a few pixels.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <random>

#include "FlowTracking.h"

using namespace roislam::frontend::detail;
using roislam::frontend::TKeyframe;

namespace
{
constexpr int kW = 640, kH = 480;
constexpr double kF = 520, kCx = 319.5, kCy = 239.5, kZ = 2.0;

/** A pinhole camera of the test (default: kW x kH, kF). */
struct TCam
{
  int w = kW, h = kH;
  double f = kF, cx = kCx, cy = kCy;
};

/** Random blobs: a texture with corners at every scale. */
cv::Mat texture(int w, int h)
{
  cv::Mat t(h, w, CV_8UC1, cv::Scalar(128));
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> x(0, w - 1), y(0, h - 1), r(2, 12), g(0, 255);
  for (int i = 0; i < 4000; ++i)
    cv::rectangle(t, cv::Rect(x(rng), y(rng), r(rng), r(rng)), cv::Scalar(g(rng)), cv::FILLED);
  cv::GaussianBlur(t, t, cv::Size(3, 3), 0.8);
  return t;
}

/** The plane z = kZ (in the first camera's frame) seen by a camera at
 *  `pose` (its pose in the first camera's frame): a homography of the
 *  texture, which covers the plane 1.5x the first view. */
cv::Mat render(const cv::Mat& tex, const mrpt::poses::CPose3D& pose, const TCam& cam = {})
{
  // Texture pixel (u, v) is the plane point ((u - tw/2) s, (v - th/2) s, kZ).
  const double s = 1.5 * kZ / cam.f * static_cast<double>(cam.w) / tex.cols * 2.0;
  const cv::Matx33d K(cam.f, 0, cam.cx, 0, cam.f, cam.cy, 0, 0, 1);
  const mrpt::poses::CPose3D inv = -pose;
  const auto R = inv.getRotationMatrix();
  cv::Matx33d M;  // texture (u, v, 1) -> camera point
  for (int r = 0; r < 3; ++r)
  {
    M(r, 0) = R(r, 0) * s;
    M(r, 1) = R(r, 1) * s;
    M(r, 2) = R(r, 0) * (-tex.cols / 2.0 * s) + R(r, 1) * (-tex.rows / 2.0 * s) + R(r, 2) * kZ +
              inv.m_coords[r];
  }
  cv::Mat out;
  cv::warpPerspective(tex, out, cv::Mat(K * M), cv::Size(cam.w, cam.h), cv::INTER_LINEAR);
  return out;
}

TKeyframe keyframeWithAnchors(const cv::Mat& grey, const TFlowParams& p, const TCam& cam = {})
{
  TKeyframe kf;
  for (const auto& k : anchorCandidates(grey, p).keypoints)
  {
    kf.anchorKeypoints.push_back(k.pt);
    kf.anchorPoints.emplace_back(
        (k.pt.x - cam.cx) / cam.f * kZ, (k.pt.y - cam.cy) / cam.f * kZ, kZ);
    kf.anchorPixels.push_back(k.pt);
  }
  return kf;
}
}  // namespace

TEST(FlowTracking, AnchorsLandWhereTheMotionProjectsThem)
{
  const TFlowParams p;
  const cv::Mat tex = texture(2 * kW, 2 * kH);
  const mrpt::poses::CPose3D moved(0.05, -0.03, 0.04, 0.03, -0.02, 0.04);
  const cv::Mat a = render(tex, mrpt::poses::CPose3D()), b = render(tex, moved);
  const TKeyframe kf = keyframeWithAnchors(a, p);
  ASSERT_GT(kf.anchorPoints.size(), 150u);
  // A window apart at least.
  for (std::size_t i = 1; i < 50; ++i)
    for (std::size_t j = 0; j < i; ++j)
      EXPECT_GE(cv::norm(kf.anchorKeypoints[i] - kf.anchorKeypoints[j]), p.window - 1e-3);

  const cv::Mat K = (cv::Mat_<double>(3, 3) << kF, 0, kCx, 0, kF, kCy, 0, 0, 1);
  const cv::Mat dist = cv::Mat::zeros(1, 5, CV_64F);
  const auto pa = flowPyramid(a, p, true), pb = flowPyramid(b, p, false);
  // Exact prediction, and one off by about 6 px (a 0.7 deg error).
  for (const auto& prediction : {moved, moved + mrpt::poses::CPose3D(0, 0, 0, 0.012, 0, 0)})
  {
    const TFlowTracks t = followAnchors(kf, pa, pb, prediction, K, dist, a.size(), cv::Rect(), p);
    ASSERT_GT(t.set.size(), kf.anchorPoints.size() * 8 / 10);
    ASSERT_EQ(t.anchorIndex.size(), t.set.size());
    std::vector<double> err;
    for (std::size_t j = 0; j < t.set.size(); ++j)
    {
      const auto& X = kf.anchorPoints[static_cast<std::size_t>(t.anchorIndex[j])];
      double x, y, z;
      moved.inverseComposePoint(X.x, X.y, X.z, x, y, z);
      const cv::Point2d truth(kF * x / z + kCx, kF * y / z + kCy);
      err.push_back(cv::norm(cv::Point2d(t.set.keypoints[j].pt) - truth));
    }
    std::sort(err.begin(), err.end());
    EXPECT_LT(err[err.size() / 2], 0.3);       // median
    EXPECT_LT(err[err.size() * 9 / 10], 1.0);  // 90th percentile
  }
}

TEST(FlowTracking, AnchorsAreNotFollowedWhereTheFrameWasDescribed)
{
  const TFlowParams p;
  const cv::Mat tex = texture(2 * kW, 2 * kH);
  const mrpt::poses::CPose3D moved(0.02, 0.01, 0.0, 0.01, 0.0, 0.0);
  const cv::Mat a = render(tex, mrpt::poses::CPose3D()), b = render(tex, moved);
  const TKeyframe kf = keyframeWithAnchors(a, p);
  const cv::Mat K = (cv::Mat_<double>(3, 3) << kF, 0, kCx, 0, kF, kCy, 0, 0, 1);
  const cv::Mat dist = cv::Mat::zeros(1, 5, CV_64F);
  const auto pa = flowPyramid(a, p, true), pb = flowPyramid(b, p, false);
  const TFlowTracks all = followAnchors(kf, pa, pb, moved, K, dist, a.size(), cv::Rect(), p);
  // The left half described (the frame's ROI): only the right half's
  // anchors are followed, and about as many as lie there.
  const cv::Rect left(0, 0, kW / 2, kH);
  const TFlowTracks rest = followAnchors(kf, pa, pb, moved, K, dist, a.size(), left, p);
  std::size_t rightOfAll = 0;
  for (const auto& k : all.set.keypoints)
    rightOfAll += k.pt.x >= kW / 2.0f + 2;
  ASSERT_GT(rightOfAll, 30u);
  EXPECT_GE(rest.set.size(), rightOfAll);
  EXPECT_LT(rest.set.size(), all.set.size() * 3 / 4);
  for (const auto& k : rest.set.keypoints)
    EXPECT_GE(k.pt.x, kW / 2.0f - 3) << "followed inside the described part";
}

TEST(FlowTracking, RegistrationViewAppendsTheAnchors)
{
  TKeyframe kf;
  kf.points = {{0, 0, 1}, {1, 0, 1}};
  kf.pixels = {{1, 1}, {2, 2}};
  kf.anchorPoints = {{0, 1, 2}};
  kf.anchorPixels = {{3, 3}};
  kf.anchorKeypoints = {{3, 3}};
  const TKeyframe v = withAnchors(kf);
  ASSERT_EQ(v.points.size(), 3u);
  EXPECT_EQ(v.points[2].y, 1);
  EXPECT_EQ(v.pixels[2], cv::Point2f(3, 3));
  EXPECT_EQ(v.features.size(), kf.features.size());
}

TEST(FlowTracking, ShiftKeepsTheTrackedImageUnder1280PxWide)
{
  EXPECT_EQ(flowShift(cv::Size(640, 480)), 0);
  EXPECT_EQ(flowShift(cv::Size(960, 540)), 0);
  EXPECT_EQ(flowShift(cv::Size(1279, 720)), 0);
  EXPECT_EQ(flowShift(cv::Size(1280, 720)), 1);
  EXPECT_EQ(flowShift(cv::Size(1920, 1080)), 1);
  EXPECT_EQ(flowShift(cv::Size(2560, 1440)), 2);
  EXPECT_EQ(flowShift(cv::Size(320, 240)), 0);
  // Pixel centres map onto pixel centres, and back exactly.
  EXPECT_FLOAT_EQ(toFlowLevel(cv::Point2f(0.5f, 1.5f), 1).x, 0.0f);
  EXPECT_FLOAT_EQ(toFlowLevel(cv::Point2f(0.5f, 1.5f), 1).y, 0.5f);
  const cv::Point2f u(123.25f, 77.75f);
  for (int shift : {0, 1, 2})
  {
    EXPECT_NEAR(fromFlowLevel(toFlowLevel(u, shift), shift).x, u.x, 1e-4);
    EXPECT_NEAR(fromFlowLevel(toFlowLevel(u, shift), shift).y, u.y, 1e-4);
  }
}

TEST(FlowTracking, AHighResolutionCameraTracksAtTheSameScale)
{
  // The same scene seen at twice the resolution: tracked one level down,
  // with about as many anchors, each a window of that level apart, landing
  // where the motion projects them (in the full-resolution pixels).
  const TFlowParams p;
  const TCam hd{2 * kW, 2 * kH, 2 * kF, 2 * kCx + 0.5, 2 * kCy + 0.5};
  cv::Mat tex;
  cv::resize(texture(2 * kW, 2 * kH), tex, cv::Size(), 2, 2, cv::INTER_LINEAR);
  const mrpt::poses::CPose3D moved(0.05, -0.03, 0.04, 0.03, -0.02, 0.04);
  const cv::Mat a = render(tex, mrpt::poses::CPose3D(), hd), b = render(tex, moved, hd);
  ASSERT_EQ(flowShift(a.size()), 1);
  const TKeyframe kf = keyframeWithAnchors(a, p, hd);
  const TKeyframe vga = keyframeWithAnchors(render(texture(2 * kW, 2 * kH), {}), p);
  ASSERT_GT(kf.anchorPoints.size(), 100u);
  EXPECT_LT(kf.anchorPoints.size(), vga.anchorPoints.size() * 3 / 2);
  for (std::size_t i = 1; i < 50; ++i)
    for (std::size_t j = 0; j < i; ++j)
      EXPECT_GE(cv::norm(kf.anchorKeypoints[i] - kf.anchorKeypoints[j]), 2 * p.window - 1e-3);

  const auto pa = flowPyramid(a, p, true), pb = flowPyramid(b, p, false);
  ASSERT_EQ(pa[0].cols, kW);  // the tracked level
  const cv::Mat K = (cv::Mat_<double>(3, 3) << hd.f, 0, hd.cx, 0, hd.f, hd.cy, 0, 0, 1);
  const cv::Mat dist = cv::Mat::zeros(1, 5, CV_64F);
  const TFlowTracks t = followAnchors(kf, pa, pb, moved, K, dist, a.size(), cv::Rect(), p);
  ASSERT_GT(t.set.size(), kf.anchorPoints.size() * 8 / 10);
  std::vector<double> err;
  for (std::size_t j = 0; j < t.set.size(); ++j)
  {
    const auto& X = kf.anchorPoints[static_cast<std::size_t>(t.anchorIndex[j])];
    double x, y, z;
    moved.inverseComposePoint(X.x, X.y, X.z, x, y, z);
    const cv::Point2d truth(hd.f * x / z + hd.cx, hd.f * y / z + hd.cy);
    err.push_back(cv::norm(cv::Point2d(t.set.keypoints[j].pt) - truth));
  }
  std::sort(err.begin(), err.end());
  EXPECT_LT(err[err.size() / 2], 0.6);       // median: twice the VGA test's, in HD pixels
  EXPECT_LT(err[err.size() * 9 / 10], 2.0);  // 90th percentile
}

TEST(FlowTracking, FeatureAnchorsAreTheStrongestAWindowApart)
{
  // flow_anchors = features: the keyframe's features, strongest first, none
  // closer to a taken one than a window of the tracked image (at 640 x 480
  // the image itself; at 1920 x 1080 twice as many of its pixels).
  const TFlowParams p;
  std::vector<cv::KeyPoint> k;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> x(0.f, 639.f), y(0.f, 479.f), r(0.f, 1.f);
  for (int i = 0; i < 600; ++i)
    k.emplace_back(cv::Point2f(x(rng), y(rng)), 31.f, -1.f, r(rng));
  for (const cv::Size image : {cv::Size(640, 480), cv::Size(1920, 1080)})
  {
    const double spacing = image.width > 640 ? 2.0 * p.window : p.window;
    const auto taken = spacedStrongest(k, image, p);
    ASSERT_GT(taken.size(), 20u);
    for (std::size_t a = 1; a < taken.size(); ++a)
      EXPECT_GE(
          k[static_cast<std::size_t>(taken[a - 1])].response,
          k[static_cast<std::size_t>(taken[a])].response);
    for (std::size_t a = 0; a < taken.size(); ++a)
      for (std::size_t b = 0; b < a; ++b)
        EXPECT_GE(
            cv::norm(
                k[static_cast<std::size_t>(taken[a])].pt -
                k[static_cast<std::size_t>(taken[b])].pt),
            spacing - 1e-4);
    // Every keypoint left out is within the spacing of a stronger one taken.
    std::vector<bool> isTaken(k.size(), false);
    for (int t : taken)
      isTaken[static_cast<std::size_t>(t)] = true;
    for (std::size_t i = 0; i < k.size(); ++i)
    {
      if (isTaken[i])
        continue;
      bool covered = false;
      for (int t : taken)
        covered = covered || (k[static_cast<std::size_t>(t)].response >= k[i].response &&
                              cv::norm(k[static_cast<std::size_t>(t)].pt - k[i].pt) < spacing);
      EXPECT_TRUE(covered) << i;
    }
  }
  // Far apart: all of them, strongest first.
  const std::vector<cv::KeyPoint> few{
      {cv::Point2f(10, 10), 31, -1, 0.2f},
      {cv::Point2f(300, 200), 31, -1, 0.9f},
      {cv::Point2f(600, 400), 31, -1, 0.5f}};
  EXPECT_EQ(spacedStrongest(few, cv::Size(640, 480), p), (std::vector<int>{1, 2, 0}));
  EXPECT_TRUE(spacedStrongest({}, cv::Size(640, 480), p).empty());
}
