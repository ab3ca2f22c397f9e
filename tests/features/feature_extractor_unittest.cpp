#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <roislam/features/CFeatureExtractor.h>

#include <opencv2/imgproc.hpp>
#include <random>

using namespace roislam::features;

namespace
{
cv::Mat texturedImage(unsigned seed = 7)
{
  cv::Mat img(480, 640, CV_8UC1);
  std::mt19937 rng(seed);
  cv::Mat noise(60, 80, CV_8UC1);
  cv::randu(noise, 0, 255);
  cv::resize(noise, img, img.size(), 0, 0, cv::INTER_CUBIC);
  std::uniform_int_distribution<int> x(0, 600), y(0, 440), c(0, 255);
  for (int i = 0; i < 150; ++i)
    cv::circle(img, cv::Point(x(rng), y(rng)), 3 + i % 12, cv::Scalar(c(rng)), cv::FILLED);
  return img;
}

CFeatureExtractor extractor(EFeatureType t, int cap)
{
  CFeatureExtractor::TOptions o;
  o.feature_type = t;
  o.max_features = cap;
  return CFeatureExtractor(o);
}
}  // namespace

TEST(CFeatureExtractor, capKeepsStrongestFirst)
{
  const cv::Mat img = texturedImage();
  for (EFeatureType t : {EFeatureType::SIFT, EFeatureType::ORB, EFeatureType::SURF})
  {
    const auto all = extractor(t, 0).extract(img);
    const auto capped = extractor(t, 50).extract(img);
    ASSERT_GT(all.size(), 50u) << toString(t);
    ASSERT_EQ(capped.size(), 50u) << toString(t);
    EXPECT_EQ(capped.descriptors.rows, 50) << toString(t);
    for (std::size_t i = 1; i < capped.size(); ++i)
      EXPECT_GE(capped.keypoints[i - 1].response, capped.keypoints[i].response) << toString(t);
  }
}

TEST(CFeatureExtractor, capWithRegionKeepsTheStrongestOfImageAndRegion)
{
  const cv::Mat img = texturedImage();
  const cv::Rect region(400, 300, 160, 120);  // 6 % of the image
  for (EFeatureType t : {EFeatureType::SIFT, EFeatureType::ORB, EFeatureType::SURF})
  {
    const auto ex = extractor(t, 40);
    const auto all = ex.extractAll(img);
    ASSERT_GT(all.size(), 200u) << toString(t);
    ASSERT_EQ(all.descriptors.rows, static_cast<int>(all.size()));
    for (std::size_t i = 1; i < all.size(); ++i)
      ASSERT_GE(all.keypoints[i - 1].response, all.keypoints[i].response) << toString(t);
    const auto capped = ex.capWithRegion(all, region);
    const auto inside = [&](const cv::KeyPoint& k) { return cv::Rect2f(region).contains(k.pt); };
    std::size_t in = 0;
    for (const auto& k : capped.keypoints)
      in += inside(k);
    // The 40 strongest overall are there, and 40 inside the region.
    EXPECT_EQ(in, 40u) << toString(t);
    for (std::size_t i = 0; i < 40; ++i)
      EXPECT_EQ(capped.keypoints[i].pt, all.keypoints[i].pt) << toString(t);
    EXPECT_GE(capped.size(), 40u + 40u - in) << toString(t);
    EXPECT_LE(capped.size(), 80u) << toString(t);
    EXPECT_EQ(capped.descriptors.rows, static_cast<int>(capped.size()));
    // No region: just the cap.
    EXPECT_EQ(ex.capWithRegion(all, cv::Rect()).size(), 40u) << toString(t);
    // No cap: unchanged.
    EXPECT_EQ(extractor(t, 0).capWithRegion(all, region).size(), all.size()) << toString(t);
  }
}

TEST(CFeatureExtractor, descriptorTypesMatchFeatureType)
{
  const cv::Mat img = texturedImage();
  EXPECT_EQ(extractor(EFeatureType::SIFT, 100).extract(img).descriptors.type(), CV_32F);
  EXPECT_EQ(extractor(EFeatureType::SURF, 100).extract(img).descriptors.type(), CV_32F);
  EXPECT_EQ(extractor(EFeatureType::ORB, 100).extract(img).descriptors.type(), CV_8U);
  EXPECT_EQ(extractor(EFeatureType::SIFT, 100).extract(img).descriptors.cols, 128);
  EXPECT_EQ(extractor(EFeatureType::ORB, 100).extract(img).descriptors.cols, 32);
}

TEST(CFeatureExtractor, colourAndGreyGiveSameFeatures)
{
  const cv::Mat grey = texturedImage();
  cv::Mat bgr;
  cv::cvtColor(grey, bgr, cv::COLOR_GRAY2BGR);
  const auto a = extractor(EFeatureType::ORB, 200).extract(grey);
  const auto b = extractor(EFeatureType::ORB, 200).extract(bgr);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(cv::norm(a.descriptors, b.descriptors, cv::NORM_HAMMING), 0);
}

TEST(TFeatureSet, subsetSelectsKeypointsInsideRectWithTheirDescriptors)
{
  const auto all = extractor(EFeatureType::ORB, 0).extract(texturedImage());
  const cv::Rect roi(200, 100, 200, 150);
  const auto sub = all.subset(roi);
  ASSERT_GT(sub.size(), 0u);
  ASSERT_LT(sub.size(), all.size());
  std::size_t inside = 0;
  for (const auto& k : all.keypoints)
    inside += cv::Rect2f(roi).contains(k.pt) ? 1 : 0;
  EXPECT_EQ(sub.size(), inside);
  // Descriptor rows follow their keypoints.
  for (std::size_t i = 0; i < sub.size(); ++i)
  {
    const auto it = std::find_if(
        all.keypoints.begin(), all.keypoints.end(),
        [&](const auto& k)
        {
          return k.pt == sub.keypoints[i].pt && k.octave == sub.keypoints[i].octave &&
                 k.angle == sub.keypoints[i].angle;
        });
    ASSERT_NE(it, all.keypoints.end());
    const int j = static_cast<int>(it - all.keypoints.begin());
    EXPECT_EQ(
        cv::norm(
            all.descriptors.row(j), sub.descriptors.row(static_cast<int>(i)), cv::NORM_HAMMING),
        0);
  }
}

TEST(CFeatureExtractorOptions, iniParsingAndErrors)
{
  mrpt::config::CConfigFileMemory cfg;
  cfg.write("FeatureExtractor", "feature_type", "SIFT");
  cfg.write("FeatureExtractor", "max_features", 600);
  CFeatureExtractor::TOptions o;
  o.loadFromConfigFile(cfg, "FeatureExtractor");
  EXPECT_EQ(o.feature_type, EFeatureType::SIFT);
  EXPECT_EQ(o.max_features, 600);

  cfg.write("FeatureExtractor", "feature_type", "brisk");
  try
  {
    o.loadFromConfigFile(cfg, "FeatureExtractor");
    FAIL() << "expected an exception";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("[FeatureExtractor] feature_type"), std::string::npos);
  }
  cfg.write("FeatureExtractor", "feature_type", "orb");
  cfg.write("FeatureExtractor", "max_features", -5);
  EXPECT_THROW(o.loadFromConfigFile(cfg, "FeatureExtractor"), std::invalid_argument);
}
