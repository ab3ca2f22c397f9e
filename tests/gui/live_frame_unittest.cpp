/* What the live view copies on the SLAM thread (makeLiveFrame): a new
 * keyframe's cloud cut to the asked number of points, images shared when
 * OpenCV owns them and copied when they wrap someone else's buffer, no
 * image unless asked, the closure list only when it changed. */
#include <gtest/gtest.h>
#include <roislam/graphslam/CSlamContext.h>
#include <roislam/gui/TLiveFrame.h>

#include <vector>

namespace
{
roislam::io::TRGBDFrame flatFrame()
{
  roislam::io::TRGBDFrame f;
  f.rgb = cv::Mat(480, 640, CV_8UC3, cv::Scalar(10, 20, 30));
  f.depth = cv::Mat(480, 640, CV_32FC1, cv::Scalar(2.0f));
  f.camera.ncols = 640;
  f.camera.nrows = 480;
  f.camera.fx(525);
  f.camera.fy(525);
  f.camera.cx(319.5);
  f.camera.cy(239.5);
  return f;
}
}  // namespace

TEST(LiveFrame, CopiesWhatTheViewNeeds)
{
  roislam::graphslam::CSlamContext ctx;
  const auto frame = flatFrame();
  roislam::frontend::TFrameResult res;
  res.frameIndex = 7;
  res.method = roislam::frontend::ETrackingMethod::Initial;
  res.pose = mrpt::poses::CPose3D();
  res.isNewKeyframe = true;
  res.newKeyframeId = 0;
  res.roi = cv::Rect(1, 2, 3, 4);
  ctx.recordFrame(res, frame);
  ASSERT_EQ(ctx.keyframeClouds().size(), 1u);
  ASSERT_GT(ctx.keyframeClouds()[0].size(), 4000u);

  const auto f = roislam::gui::makeLiveFrame(res, frame, ctx, true, 1000, 0);
  EXPECT_EQ(f.index, 7u);
  EXPECT_EQ(f.roi, res.roi);
  ASSERT_TRUE(f.cloud);
  EXPECT_LE(f.cloud->size(), 1000u);
  EXPECT_GE(f.cloud->size(), 900u);
  // Colours as 8 bits (BGR 10,20,30 -> RGB 30,20,10), points 2 m ahead.
  EXPECT_EQ((*f.cloud)[0].r, 30);
  EXPECT_EQ((*f.cloud)[0].b, 10);
  EXPECT_FLOAT_EQ((*f.cloud)[0].pt.z, 2.0f);
  // Shared, not copied.
  EXPECT_EQ(f.rgb.data, frame.rgb.data);
  EXPECT_EQ(f.depth.data, frame.depth.data);
  EXPECT_FALSE(f.loops);  // none seen, none now

  // Without the image: none kept; a changed closure count sends the list.
  const auto g = roislam::gui::makeLiveFrame(res, frame, ctx, false, 1000, 3);
  EXPECT_TRUE(g.rgb.empty());
  ASSERT_TRUE(g.loops);
  EXPECT_TRUE(g.loops->empty());

  // An image wrapping a foreign buffer is copied (the buffer may go).
  std::vector<unsigned char> buffer(480 * 640 * 3, 5);
  auto wrapped = frame;
  wrapped.rgb = cv::Mat(480, 640, CV_8UC3, buffer.data());
  const auto h = roislam::gui::makeLiveFrame(res, wrapped, ctx, true, 1000, 0);
  EXPECT_NE(h.rgb.data, buffer.data());
  EXPECT_EQ(h.rgb.at<cv::Vec3b>(10, 10), cv::Vec3b(5, 5, 5));
}
