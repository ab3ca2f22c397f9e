/* Depth registration of unregistered sensors (observationToFrame): the depth
 * lands where the distorted colour camera sees it, and a depth grid larger
 * than the colour grid is handled (OpenCV 4.6's registerDepth alone crashes). */
#include <gtest/gtest.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/img/CImage.h>
#include <roislam/io/ObservationConversion.h>

#include <cmath>
#include <opencv2/calib3d.hpp>

using namespace roislam::io;

namespace
{
mrpt::img::TCamera pinhole(int w, int h, double f)
{
  mrpt::img::TCamera c;
  c.ncols = static_cast<uint32_t>(w);
  c.nrows = static_cast<uint32_t>(h);
  c.fx(f);
  c.fy(f);
  c.cx(0.5 * (w - 1));
  c.cy(0.5 * (h - 1));
  return c;
}
}  // namespace

// Depth camera and colour camera at the same place, the depth camera with a
// denser grid (128x96 into 64x48) and the colour camera with strong radial
// distortion; the scene is a step, Z = 1 m left of x/z = 0.4 and Z = 2 m
// right of it. Each colour pixel must get the depth of the side its own
// (undistorted) ray falls on: a pinhole re-projection would put the step up
// to several pixels off.
TEST(DepthRegistration, DistortedColourAndDenserDepthGrid)
{
  const double edge = 0.4;
  const auto dc = pinhole(128, 96, 100.0);
  auto cc = pinhole(64, 48, 50.0);
  cc.k1(0.6);
  cv::Mat mm(96, 128, CV_16UC1);
  for (int r = 0; r < mm.rows; ++r)
    for (int c = 0; c < mm.cols; ++c)
      mm.at<uint16_t>(r, c) = (c - dc.cx()) / dc.fx() < edge ? 1000 : 2000;
  auto obs = observationFromRawDepth(mm, 0.001f, dc, 1.0);
  obs->cameraParamsIntensity = cc;
  // Both cameras' optical frames coincide: the MRPT depth frame's fixed twist.
  obs->relativePoseIntensityWRTDepth =
      mrpt::poses::CPose3D(0, 0, 0, mrpt::DEG2RAD(-90.0), 0, mrpt::DEG2RAD(-90.0));
  obs->intensityImage =
      mrpt::img::CImage(cv::Mat(48, 64, CV_8UC3, cv::Scalar(90, 120, 150)), mrpt::img::DEEP_COPY);
  obs->hasIntensityImage = true;
  const TRGBDFrame f = observationToFrame(*obs, "test");
  ASSERT_EQ(f.depth.size(), cv::Size(64, 48));

  const cv::Matx33d K(cc.fx(), 0, cc.cx(), 0, cc.fy(), cc.cy(), 0, 0, 1);
  const std::vector<double> dist = {cc.k1(), 0, 0, 0, 0};
  int valid = 0, wrong = 0, checked = 0;
  for (int v = 0; v < 48; ++v)
    for (int u = 0; u < 64; ++u)
    {
      std::vector<cv::Point2f> px{cv::Point2f(static_cast<float>(u), static_cast<float>(v))}, n;
      cv::undistortPoints(px, n, K, dist);
      const float z = f.depth.at<float>(v, u);
      EXPECT_FALSE(std::isnan(z)) << u << "," << v;
      if (z > 0)
        ++valid;
      // Pixels within a pixel of the step may take either side.
      if (!(z > 0) || std::abs(n[0].x - edge) * cc.fx() < 1.0)
        continue;
      ++checked;
      const float expected = n[0].x < edge ? 1.0f : 2.0f;
      if (std::abs(z - expected) > 1e-3f)
        ++wrong;
    }
  // The colour image is wider than the depth camera's view at its corners
  // (barrel distortion shows more), so a few pixels have no depth.
  EXPECT_GT(valid, 0.85 * 64 * 48);
  EXPECT_GT(checked, 0.8 * 64 * 48);
  EXPECT_EQ(wrong, 0);
}
