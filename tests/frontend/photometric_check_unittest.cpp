// The colour image as the arbiter between the features and depth ICP
// (libs/frontend/src/PhotometricCheck.h): samples of a keyframe carried onto
// a later frame of the ray-cast room by the true relative pose and by a
// wrong one; which one the sign test picks, and what it ignores.
#include <gtest/gtest.h>
#include <mrpt/core/bits_math.h>

#include <opencv2/imgproc.hpp>

#include "PhotometricCheck.h"
#include "SyntheticRoom.h"

using roislam::frontend::detail::comparePhotometric;
using roislam::frontend::detail::photoSamples;
using roislam::frontend::detail::TPhotoSamples;
using roislam::frontend::detail::TRigid;
using roislam::frontend::testing::renderRoom;
using roislam::frontend::testing::syntheticCamera;
using roislam::geometry::TDepthRule;

namespace
{
cv::Mat cameraMatrix()
{
  const auto c = syntheticCamera();
  return (cv::Mat_<double>(3, 3) << c.fx(), 0, c.cx(), 0, c.fy(), c.cy(), 0, 0, 1);
}
/** Depth 0.3-8 m (the room's far walls), depth edges at 5 % (the front end's). */
TDepthRule rule()
{
  TDepthRule r;
  r.min_depth_m = 0.3;
  r.max_depth_m = 8.0;
  r.depth_discontinuity_m = 0.05;
  return r;
}
cv::Mat grey(const roislam::io::TRGBDFrame& f)
{
  cv::Mat g;
  cv::cvtColor(f.rgb, g, cv::COLOR_BGR2GRAY);
  return g;
}

struct TPair
{
  TPhotoSamples samples;
  cv::Mat current;
  TRigid truth;  // x_keyframe = truth x_current
};
/** A keyframe and a frame 4 cm and 2 degrees on, as the front end sees them. */
TPair keyframeAndFrame(double contrast = 60)
{
  const mrpt::poses::CPose3D a(0.1, -0.05, 0.2, mrpt::DEG2RAD(5.0), 0, 0);
  const mrpt::poses::CPose3D b =
      a + mrpt::poses::CPose3D(0.03, 0.01, 0.025, mrpt::DEG2RAD(2.0), mrpt::DEG2RAD(-1.0), 0);
  const auto key = renderRoom(a, contrast, 0, 0.0);
  const auto cur = renderRoom(b, contrast, 1, 0.033);
  TPair p;
  p.samples = photoSamples(grey(key), key.depth, cameraMatrix(), cv::Mat(), rule());
  p.current = grey(cur);
  p.truth = TRigid::fromPose(b - a);
  return p;
}
TRigid moved(const TRigid& T, double dx, double yawDeg)
{
  return TRigid::fromPose(T.toPose() + mrpt::poses::CPose3D(dx, 0, 0, mrpt::DEG2RAD(yawDeg), 0, 0));
}
}  // namespace

TEST(PhotometricCheck, SamplesAreSpreadAndLandOnTheirOwnGreyLevel)
{
  const auto p = keyframeAndFrame();
  // One per 12 x 12 cell at most (40 x 53 cells), most cells textured.
  EXPECT_GT(p.samples.points.size(), 800u);
  EXPECT_LE(p.samples.points.size(), 40u * 53u);
  // Carried by the identity onto the keyframe itself, every sample is seen
  // and no pose is closer than the other.
  const auto key =
      renderRoom(mrpt::poses::CPose3D(0.1, -0.05, 0.2, mrpt::DEG2RAD(5.0), 0, 0), 60, 0, 0);
  const auto c =
      comparePhotometric(p.samples, grey(key), cameraMatrix(), cv::Mat(), TRigid(), TRigid());
  EXPECT_EQ(c.compared, p.samples.points.size());
  EXPECT_EQ(c.firstCloser + c.secondCloser, 0u);
  EXPECT_EQ(c.z(), 0.0);
}

TEST(PhotometricCheck, TheTruePoseWinsAgainstOneACentimetreOff)
{
  const auto p = keyframeAndFrame();
  for (const auto& [dx, yaw] : {std::pair{0.01, 0.0}, {0.0, 0.5}, {0.005, 0.25}})
  {
    const TRigid wrong = moved(p.truth, dx, yaw);
    const auto c =
        comparePhotometric(p.samples, p.current, cameraMatrix(), cv::Mat(), p.truth, wrong);
    EXPECT_GT(c.compared, 500u);
    EXPECT_LT(c.z(), -5.0) << dx << " m, " << yaw << " deg: " << c.firstCloser << " / "
                           << c.secondCloser;
    // The order of the two does not matter.
    const auto swapped =
        comparePhotometric(p.samples, p.current, cameraMatrix(), cv::Mat(), wrong, p.truth);
    EXPECT_DOUBLE_EQ(swapped.z(), -c.z());
  }
}

TEST(PhotometricCheck, AnExposureChangeDoesNotDecide)
{
  const auto p = keyframeAndFrame();
  cv::Mat brighter;
  p.current.convertTo(brighter, CV_8U, 1.0, 35.0);
  const auto c = comparePhotometric(
      p.samples, brighter, cameraMatrix(), cv::Mat(), moved(p.truth, 0.01, 0.0), p.truth);
  EXPECT_GT(c.z(), 5.0);
}

TEST(PhotometricCheck, NoSamplesWithoutGreyEdgesNorOnDepthEdges)
{
  // A uniform room: nothing to compare, so no verdict.
  const auto flat = keyframeAndFrame(0.0);
  EXPECT_TRUE(flat.samples.points.empty());
  const auto c = comparePhotometric(
      flat.samples, flat.current, cameraMatrix(), cv::Mat(), flat.truth,
      moved(flat.truth, 0.02, 0));
  EXPECT_EQ(c.compared, 0u);
  EXPECT_EQ(c.z(), 0.0);

  // A grey edge exactly on a depth step (a silhouette) gives no sample: the
  // pixel's depth there could be either side's.
  cv::Mat g(480, 640, CV_8UC1, cv::Scalar(60)), depth(480, 640, CV_32FC1, cv::Scalar(2.0F));
  g.colRange(320, 640).setTo(200);
  depth.colRange(320, 640).setTo(1.0F);
  const auto s = photoSamples(g, depth, cameraMatrix(), cv::Mat(), rule());
  EXPECT_TRUE(s.points.empty());
  // The same grey edge on a continuous surface is sampled, at its depth.
  depth.setTo(2.0F);
  const auto s2 = photoSamples(g, depth, cameraMatrix(), cv::Mat(), rule());
  ASSERT_FALSE(s2.points.empty());
  for (const auto& x : s2.points)
    EXPECT_NEAR(x.z(), 2.0, 1e-6);
}
