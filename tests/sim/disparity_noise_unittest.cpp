// CDisparityNoiseModel: quantised disparities, the modelled spread, lateral
// jitter that smears edges, holes kept, determinism.
#include <gtest/gtest.h>
#include <roislam/sim/CDisparityNoiseModel.h>

#include <cmath>
#include <opencv2/core.hpp>

using roislam::io::TSensorDescription;
using roislam::sim::CDisparityNoiseModel;

TEST(DisparityNoise, QuantisedWithTheModelledSpread)
{
  TSensorDescription::TDepthNoise p;
  p.model = "disparity";
  p.lateral_sigma_px = 0;  // the jitter alone is tested below
  const CDisparityNoiseModel m(p);
  for (const float z : {1.0f, 2.0f, 3.0f})
  {
    // A gently slanted plane, so that the true disparities fall anywhere
    // between two quantisation steps (sigma() averages over that).
    cv::Mat clean(200, 200, CV_32FC1);
    for (int r = 0; r < clean.rows; ++r)
      for (int c = 0; c < clean.cols; ++c)
        clean.at<float>(r, c) = z * (1 + 0.05f * (c - 100) / 100.0f);
    cv::Mat d = clean.clone();
    mrpt::random::CRandomGenerator rng(3);
    m.corruptDepth(d, rng);
    cv::Scalar mean, sd;
    cv::meanStdDev(d - clean, mean, sd);
    EXPECT_NEAR(mean[0], 0, 0.1 * p.sigma(z)) << z;
    EXPECT_NEAR(sd[0], p.sigma(z), 0.1 * p.sigma(z)) << z;
    for (int k = 0; k < 50; ++k)
    {
      const double steps = p.disparity_bf * p.disparity_steps_per_px / d.at<float>(k, 3 * k);
      EXPECT_NEAR(steps, std::round(steps), 1e-3 * steps);
    }
  }
  // The spread grows with z^2 (a disparity camera's law).
  EXPECT_NEAR(p.sigma(3.0) / p.sigma(1.5), 4.0, 1e-9);
}

TEST(DisparityNoise, EdgesSmearHolesStayAndSeedsRepeat)
{
  TSensorDescription::TDepthNoise p;
  p.model = "disparity";
  p.lateral_sigma_px = 1.0;
  const CDisparityNoiseModel m(p);
  cv::Mat d(60, 100, CV_32FC1, cv::Scalar(1.0f));
  d(cv::Rect(50, 0, 50, 60)).setTo(2.0f);
  d(cv::Rect(10, 10, 5, 5)).setTo(0.0f);
  cv::Mat a = d.clone(), b = d.clone();
  mrpt::random::CRandomGenerator r1(11), r2(11);
  m.corruptDepth(a, r1);
  m.corruptDepth(b, r2);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
  // Flying pixels between the two surfaces next to the step, none far from it.
  int between = 0;
  for (int r = 0; r < 60; ++r)
    for (int c = 47; c <= 52; ++c)
    {
      const float z = a.at<float>(r, c);
      between += z > 1.1f && z < 1.9f ? 1 : 0;
    }
  EXPECT_GT(between, 10);
  for (int r = 0; r < 60; ++r)
    EXPECT_LT(std::abs(a.at<float>(r, 30) - 1.0f), 0.05f);
  // The hole's centre has no reading.
  EXPECT_EQ(a.at<float>(12, 12), 0.0f);
}
