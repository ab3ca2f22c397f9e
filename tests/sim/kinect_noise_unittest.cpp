// CKinectNoiseModel: noise magnitude, edge dropout, range limits, determinism.
#include <gtest/gtest.h>
#include <roislam/sim/CKinectNoiseModel.h>

#include <cmath>
#include <opencv2/core.hpp>

using roislam::sim::CKinectNoiseModel;

TEST(KinectNoise, SigmaFollowsNguyenModel)
{
  const CKinectNoiseModel m(CKinectNoiseModel::TParams{});
  EXPECT_NEAR(m.depthSigma(0.4), 0.0012, 1e-12);
  EXPECT_NEAR(m.depthSigma(2.4), 0.0012 + 0.0019 * 4.0, 1e-12);
}

TEST(KinectNoise, DepthNoiseHasTheModelledSpread)
{
  const CKinectNoiseModel m(CKinectNoiseModel::TParams{});
  cv::Mat d(200, 200, CV_32FC1, cv::Scalar(3.0f));
  mrpt::random::CRandomGenerator rng(5);
  m.corruptDepth(d, rng);
  // Interior pixels only (the image border has no invalid neighbours either).
  cv::Scalar mean, sd;
  cv::meanStdDev(d(cv::Rect(1, 1, 198, 198)), mean, sd);
  const double expected = m.depthSigma(3.0);
  EXPECT_NEAR(mean[0], 3.0, 0.001);
  EXPECT_NEAR(sd[0], expected, 0.05 * expected);
  EXPECT_EQ(cv::countNonZero(d == 0), 0);
}

TEST(KinectNoise, DropsDepthAtDiscontinuitiesOnly)
{
  const CKinectNoiseModel m(CKinectNoiseModel::TParams{});
  cv::Mat d(50, 100, CV_32FC1, cv::Scalar(1.0f));
  d(cv::Rect(50, 0, 50, 50)).setTo(2.0f);  // a step at column 50
  mrpt::random::CRandomGenerator rng(1);
  m.corruptDepth(d, rng);
  for (int r = 0; r < 50; ++r)
  {
    EXPECT_EQ(d.at<float>(r, 49), 0.0f);
    EXPECT_EQ(d.at<float>(r, 50), 0.0f);
    EXPECT_GT(d.at<float>(r, 47), 0.9f);
    EXPECT_GT(d.at<float>(r, 52), 1.9f);
  }
}

TEST(KinectNoise, RangeLimits)
{
  cv::Mat d = (cv::Mat_<float>(1, 4) << 0.2f, 1.0f, 3.9f, 4.2f);
  CKinectNoiseModel::applyRange(d, 0.4, 4.0);
  EXPECT_EQ(d.at<float>(0), 0.0f);
  EXPECT_EQ(d.at<float>(1), 1.0f);
  EXPECT_EQ(d.at<float>(2), 3.9f);
  EXPECT_EQ(d.at<float>(3), 0.0f);
}

TEST(KinectNoise, ColourNoiseIsDeterministicPerSeed)
{
  const CKinectNoiseModel m(CKinectNoiseModel::TParams{});
  cv::Mat a(64, 64, CV_8UC3, cv::Scalar(100, 100, 100)), b = a.clone(), c = a.clone();
  mrpt::random::CRandomGenerator r1(3), r2(3), r3(4);
  m.corruptColour(a, r1);
  m.corruptColour(b, r2);
  m.corruptColour(c, r3);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(a, c, cv::NORM_L1), 0.0);
  cv::Scalar mean, sd;
  cv::meanStdDev(a.reshape(1), mean, sd);
  EXPECT_NEAR(sd[0], 2.0, 0.3);
}
