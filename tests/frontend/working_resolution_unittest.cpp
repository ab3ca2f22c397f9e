// The features' working resolution (libs/frontend/src WorkingResolution.h):
// which cameras are halved, and extraction on the halved image of a region
// given in the camera's pixels: only the region's keypoints come back, in
// the camera's pixels, where the full-resolution detector finds them, for a
// quarter of the pixels.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <random>

#include "WorkingResolution.h"

using namespace roislam::frontend::detail;
using roislam::features::CFeatureExtractor;
using roislam::features::EFeatureType;

namespace
{
/** Random blocks, blurred: corners at every scale. */
cv::Mat blocks(int w, int h)
{
  cv::Mat t(h, w, CV_8UC1, cv::Scalar(128));
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> x(0, w - 1), y(0, h - 1), r(6, 40), g(0, 255);
  for (int i = 0; i < 1500; ++i)
    cv::rectangle(t, cv::Rect(x(rng), y(rng), r(rng), r(rng)), cv::Scalar(g(rng)), cv::FILLED);
  cv::GaussianBlur(t, t, cv::Size(5, 5), 1.2);
  return t;
}

CFeatureExtractor extractor(EFeatureType type)
{
  CFeatureExtractor::TOptions o;
  o.feature_type = type;
  o.max_features = 400;
  return CFeatureExtractor(o);
}
}  // namespace

TEST(WorkingResolution, OnlyCamerasWiderThan1280PxAreHalved)
{
  EXPECT_EQ(featureShift(cv::Size(640, 480), true), 0);
  EXPECT_EQ(featureShift(cv::Size(960, 540), true), 0);
  EXPECT_EQ(featureShift(cv::Size(1280, 720), true), 1);
  EXPECT_EQ(featureShift(cv::Size(1920, 1080), true), 1);
  EXPECT_EQ(featureShift(cv::Size(2560, 1440), true), 2);
  EXPECT_EQ(featureShift(cv::Size(1920, 1080), false), 0);
  const cv::Mat g = blocks(1920, 1080);
  EXPECT_EQ(reduced(g, 0).data, g.data);  // no copy
  EXPECT_EQ(reduced(g, 1).size(), cv::Size(960, 540));
  EXPECT_EQ(reduced(g, 2).size(), cv::Size(480, 270));
}

TEST(WorkingResolution, ARegionIsDescribedAtHalfResolutionInTheCamerasPixels)
{
  const cv::Mat full = blocks(1920, 1080);
  const TWorkingImage half{reduced(full, 1), 1, full.size()};
  const cv::Rect region(701, 333, 601, 401);
  for (EFeatureType type : {EFeatureType::ORB, EFeatureType::SIFT, EFeatureType::SURF})
  {
    const auto e = extractor(type);
    std::size_t pxFull = 0, pxHalf = 0;
    const auto atFull = e.extractIn(full, region, 200, &pxFull);
    const auto atHalf = extractIn(e, half, region, 200, &pxHalf);
    ASSERT_GT(atHalf.size(), 50u) << static_cast<int>(type);
    EXPECT_LE(atHalf.size(), 200u);
    EXPECT_EQ(atHalf.descriptors.rows, static_cast<int>(atHalf.size()));
    // A quarter of the region's pixels; the detector's margin, the same in
    // its own pixels at either resolution, adds a few percent.
    const double share = static_cast<double>(pxHalf) / static_cast<double>(pxFull);
    EXPECT_GT(share, 0.25) << static_cast<int>(type);
    EXPECT_LT(share, 1.0 / 3.0) << static_cast<int>(type);
    const cv::Rect2f box(region);
    std::vector<double> nearest;
    for (const auto& k : atHalf.keypoints)
    {
      EXPECT_TRUE(box.contains(k.pt)) << k.pt;
      double best = 1e9;
      for (const auto& f : atFull.keypoints)
        best = std::min(best, static_cast<double>(cv::norm(f.pt - k.pt)));
      nearest.push_back(best);
    }
    // The same corners: most within a few of the camera's pixels of a
    // full-resolution keypoint (a wrong mapping, e.g. without the factor 2,
    // puts them hundreds of pixels off).
    std::sort(nearest.begin(), nearest.end());
    EXPECT_LT(nearest[nearest.size() / 2], 3.0) << static_cast<int>(type);
  }
}

TEST(WorkingResolution, FullResolutionIsTheExtractorItself)
{
  const cv::Mat full = blocks(1280, 720);
  const TWorkingImage same{full, 0, full.size()};
  const auto e = extractor(EFeatureType::ORB);
  std::size_t a = 0, b = 0;
  const cv::Rect region(100, 100, 500, 300);
  const auto direct = e.extractIn(full, region, 150, &a);
  const auto viaHelper = extractIn(e, same, region, 150, &b);
  EXPECT_EQ(a, b);
  ASSERT_EQ(direct.size(), viaHelper.size());
  for (std::size_t i = 0; i < direct.size(); ++i)
    EXPECT_EQ(direct.keypoints[i].pt, viaHelper.keypoints[i].pt);
  EXPECT_EQ(cv::norm(direct.descriptors, viaHelper.descriptors, cv::NORM_L1), 0.0);
}

TEST(WorkingResolution, KeypointSizesScaleWithTheirPositions)
{
  roislam::features::TFeatureSet s;
  s.keypoints.emplace_back(cv::Point2f(10.f, 20.f), 31.f);
  toImagePixels(s, 1);
  EXPECT_FLOAT_EQ(s.keypoints[0].pt.x, 20.5f);
  EXPECT_FLOAT_EQ(s.keypoints[0].pt.y, 40.5f);
  EXPECT_FLOAT_EQ(s.keypoints[0].size, 62.f);
  toImagePixels(s, 0);
  EXPECT_FLOAT_EQ(s.keypoints[0].pt.x, 20.5f);
}
