/* The live view's image panel (drawFrameOverlay, colouriseDepth): the ROI
 * box is drawn where the ROI is, features inside the ROI / tracking region
 * are green and the rest orange (all green in traditional mode), a
 * fallback's caption is red, and missing depth stays black. */
#include <gtest/gtest.h>
#include <roislam/gui/FrameOverlay.h>

using roislam::gui::TLiveFrame;
using roislam::gui::TOverlayColours;

namespace
{
TLiveFrame grey640()
{
  TLiveFrame f;
  f.rgb = cv::Mat(480, 640, CV_8UC3, cv::Scalar(128, 128, 128));
  f.method = roislam::frontend::ETrackingMethod::RoiFeatures;
  return f;
}

bool near(const cv::Vec3b& p, const cv::Scalar& c)
{
  return std::abs(p[0] - c[0]) < 40 && std::abs(p[1] - c[1]) < 40 && std::abs(p[2] - c[2]) < 40;
}
}  // namespace

TEST(FrameOverlay, RoiBoxAndFeaturesInTwoColours)
{
  auto f = grey640();
  f.roi = cv::Rect(200, 200, 200, 150);
  f.featurePixels = {{300, 275}, {50, 400}};
  EXPECT_TRUE(roislam::gui::isTrackedFeature(f, f.featurePixels[0], true));
  EXPECT_FALSE(roislam::gui::isTrackedFeature(f, f.featurePixels[1], true));
  EXPECT_TRUE(roislam::gui::isTrackedFeature(f, f.featurePixels[1], false));
  // The tracking region, when there is one, decides instead of the ROI.
  auto g = f;
  g.region = cv::Rect(0, 300, 200, 180);
  EXPECT_TRUE(roislam::gui::isTrackedFeature(g, g.featurePixels[1], true));
  EXPECT_FALSE(roislam::gui::isTrackedFeature(g, g.featurePixels[0], true));

  const cv::Mat img = drawFrameOverlay(f, true);
  ASSERT_EQ(img.size(), f.rgb.size());
  EXPECT_TRUE(near(img.at<cv::Vec3b>(275, 200), TOverlayColours::roiBox()));       // left edge
  EXPECT_TRUE(near(img.at<cv::Vec3b>(349, 300), TOverlayColours::roiBox()));       // bottom edge
  EXPECT_TRUE(near(img.at<cv::Vec3b>(275, 300 + 4), TOverlayColours::tracked()));  // its circle
  EXPECT_TRUE(near(img.at<cv::Vec3b>(400, 50 + 4), TOverlayColours::extension()));
  EXPECT_TRUE(near(img.at<cv::Vec3b>(100, 600), cv::Scalar(128, 128, 128)));  // untouched
  // The input image is not drawn on.
  EXPECT_TRUE(near(f.rgb.at<cv::Vec3b>(275, 200), cv::Scalar(128, 128, 128)));
}

TEST(FrameOverlay, FallbackCaptionIsRed)
{
  auto f = grey640();
  f.method = roislam::frontend::ETrackingMethod::DepthIcp;
  const cv::Mat img = drawFrameOverlay(f, true);
  int red = 0;
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 200; ++x)
      red += near(img.at<cv::Vec3b>(y, x), TOverlayColours::fallback());
  EXPECT_GT(red, 20);
  f.method = roislam::frontend::ETrackingMethod::RoiFeatures;
  const cv::Mat ok = drawFrameOverlay(f, true);
  red = 0;
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 200; ++x)
      red += near(ok.at<cv::Vec3b>(y, x), TOverlayColours::fallback());
  EXPECT_EQ(red, 0);
}

TEST(FrameOverlay, DepthFalseColourKeepsHolesBlack)
{
  cv::Mat depth(10, 10, CV_32FC1, cv::Scalar(2.0f));
  depth.at<float>(3, 3) = 0;
  const cv::Mat c = roislam::gui::colouriseDepth(depth, 5.0);
  ASSERT_EQ(c.type(), CV_8UC3);
  EXPECT_EQ(c.at<cv::Vec3b>(3, 3), cv::Vec3b(0, 0, 0));
  EXPECT_NE(c.at<cv::Vec3b>(5, 5), cv::Vec3b(0, 0, 0));
  EXPECT_TRUE(roislam::gui::colouriseDepth(cv::Mat(), 5.0).empty());
}
