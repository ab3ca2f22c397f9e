// CCvOdometry: options round trip and validation, and the frame-to-frame
// composition on frames whose motion is known.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <roislam/reference/CCvOdometry.h>

#include <opencv2/imgproc.hpp>

using roislam::reference::CCvOdometry;

namespace
{
mrpt::img::TCamera camera()
{
  mrpt::img::TCamera c;
  c.ncols = 320;
  c.nrows = 240;
  c.setIntrinsicParamsFromValues(300, 300, 159.5, 119.5);
  c.dist.fill(0);
  c.distortion = mrpt::img::DistortionModel::none;
  return c;
}

/** A fronto-parallel textured plane at depth z seen by camera(), the camera
 *  shifted by tx along its x axis (colour: the texture moved by -fx tx / z). */
roislam::io::TRGBDFrame planeFrame(double tx, double z, std::size_t index)
{
  const auto c = camera();
  cv::Mat texture(c.nrows, c.ncols + 80, CV_8UC1);
  cv::RNG rng(7);
  rng.fill(texture, cv::RNG::UNIFORM, 0, 255);
  cv::GaussianBlur(texture, texture, cv::Size(7, 7), 2.0);
  roislam::io::TRGBDFrame f;
  f.index = index;
  f.timestamp = index / 30.0;
  const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, -40 - c.fx() * tx / z, 0, 1, 0);
  cv::Mat grey;
  cv::warpAffine(texture, grey, shift, cv::Size(c.ncols, c.nrows), cv::INTER_LINEAR);
  cv::cvtColor(grey, f.rgb, cv::COLOR_GRAY2BGR);
  f.depth = cv::Mat(c.nrows, c.ncols, CV_32FC1, cv::Scalar(z));
  f.camera = c;
  return f;
}
}  // namespace

TEST(CCvOdometry, optionsRoundTrip)
{
  CCvOdometry::TOptions o;
  o.method = "icp";
  o.min_depth = 0.3;
  o.max_depth = 6;
  o.max_depth_diff = 0.05;
  o.max_points_part = 0.2;
  o.undistort = false;
  mrpt::config::CConfigFileMemory cfg;
  o.saveToConfigFile(cfg, "CvOdometry");
  CCvOdometry::TOptions back;
  back.loadFromConfigFile(cfg, "CvOdometry");
  EXPECT_EQ(back.method, "icp");
  EXPECT_DOUBLE_EQ(back.min_depth, 0.3);
  EXPECT_DOUBLE_EQ(back.max_depth, 6);
  EXPECT_DOUBLE_EQ(back.max_depth_diff, 0.05);
  EXPECT_DOUBLE_EQ(back.max_points_part, 0.2);
  EXPECT_FALSE(back.undistort);
}

TEST(CCvOdometry, badValuesNameTheKey)
{
  const auto expectError = [](const std::string& key, const std::string& value)
  {
    mrpt::config::CConfigFileMemory cfg;
    cfg.write("CvOdometry", key, value);
    CCvOdometry::TOptions o;
    try
    {
      o.loadFromConfigFile(cfg, "CvOdometry");
      ADD_FAILURE() << key << " = " << value << " was accepted";
    }
    catch (const std::invalid_argument& e)
    {
      EXPECT_NE(std::string(e.what()).find("[CvOdometry] " + key), std::string::npos) << e.what();
    }
  };
  expectError("method", "fast");
  expectError("min_depth", "-1");
  expectError("max_depth", "0");
  expectError("max_depth_diff", "abc");
  expectError("max_points_part", "1.5");
  expectError("undistort", "maybe");
}

TEST(CCvOdometry, classNames)
{
  EXPECT_EQ(CCvOdometry::className("rgbd"), "RgbdOdometry");
  EXPECT_EQ(CCvOdometry::className("icp"), "ICPOdometry");
  EXPECT_EQ(CCvOdometry::className("rgbdicp"), "RgbdICPOdometry");
  EXPECT_THROW(CCvOdometry::className("x"), std::invalid_argument);
}

TEST(CCvOdometry, firstFrameIsTheOriginAndSizesAreChecked)
{
  CCvOdometry odo({}, camera());
  const auto s = odo.process(planeFrame(0, 1.5, 0));
  EXPECT_TRUE(s.tracked);
  EXPECT_NEAR(s.pose.norm(), 0, 1e-12);
  auto wrong = planeFrame(0, 1.5, 1);
  wrong.depth = cv::Mat(10, 10, CV_32FC1, cv::Scalar(1));
  EXPECT_THROW(odo.process(wrong), std::invalid_argument);
}

TEST(CCvOdometry, photometricOdometryFollowsAKnownShift)
{
  // A plane seen head-on constrains the lateral shift through the texture
  // alone, which is what RgbdOdometry measures; 1 cm per frame to the right.
  CCvOdometry::TOptions o;
  o.method = "rgbd";
  CCvOdometry odo(o, camera());
  CCvOdometry::TStep s;
  for (int k = 0; k < 4; ++k)
    s = odo.process(planeFrame(0.01 * k, 1.5, k));
  EXPECT_TRUE(s.tracked);
  EXPECT_NEAR(s.pose.x(), 0.03, 0.003);
  EXPECT_NEAR(s.pose.y(), 0, 0.003);
  EXPECT_NEAR(s.pose.z(), 0, 0.003);
}
