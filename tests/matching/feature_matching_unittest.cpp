#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <roislam/features/CFeatureExtractor.h>
#include <roislam/matching/CFeatureIndex.h>
#include <roislam/matching/CFeatureMatcher.h>
#include <roislam/matching/CHomographyLocator.h>

#include <opencv2/imgproc.hpp>
#include <random>

using namespace roislam;
using features::EFeatureType;

namespace
{
// A scene: mid-grey background with mild noise, one strongly textured patch.
cv::Mat sceneWithPatch(const cv::Rect& patch, unsigned seed)
{
  cv::Mat img(480, 640, CV_8UC1);
  cv::randn(img, 128, 4);
  std::mt19937 rng(seed);
  cv::Mat tex(patch.height / 6, patch.width / 6, CV_8UC1);
  cv::randu(tex, 0, 255);
  cv::Mat big;
  cv::resize(tex, big, patch.size(), 0, 0, cv::INTER_LINEAR);
  std::uniform_int_distribution<int> x(0, patch.width - 20), y(0, patch.height - 20);
  for (int i = 0; i < 40; ++i)
    cv::rectangle(big, cv::Rect(x(rng), y(rng), 12, 7), cv::Scalar(i % 2 ? 0 : 255), cv::FILLED);
  big.copyTo(img(patch));
  return img;
}

features::TFeatureSet extract(EFeatureType t, const cv::Mat& img)
{
  features::CFeatureExtractor::TOptions o;
  o.feature_type = t;
  o.max_features = 1000;
  return features::CFeatureExtractor(o).extract(img);
}

struct TWarpCase
{
  EFeatureType type;
  matching::EMatcherType matcher;
};

/** `got` pairs the same query and train features as `expected`, in order. */
void expectSameMatches(const std::vector<cv::DMatch>& got, const std::vector<cv::DMatch>& expected)
{
  ASSERT_EQ(got.size(), expected.size());
  for (std::size_t i = 0; i < got.size(); ++i)
  {
    EXPECT_EQ(got[i].queryIdx, expected[i].queryIdx) << i;
    EXPECT_EQ(got[i].trainIdx, expected[i].trainIdx) << i;
  }
}
}  // namespace

class WarpedPatch : public ::testing::TestWithParam<TWarpCase>
{
};

TEST_P(WarpedPatch, isReidentifiedAndLocated)
{
  const cv::Rect patch(200, 150, 240, 180);
  const cv::Mat ref = sceneWithPatch(patch, 11);
  // Known homography: rotation 12 deg, scale 1.1, translation, mild perspective.
  const cv::Point2f c(320, 240);
  cv::Mat A = cv::getRotationMatrix2D(c, 12, 1.1);
  cv::Mat H = cv::Mat::eye(3, 3, CV_64F);
  A.copyTo(H(cv::Rect(0, 0, 3, 2)));
  H.at<double>(0, 2) += 25;
  H.at<double>(1, 2) -= 15;
  H.at<double>(2, 0) = 2e-5;
  cv::Mat other;
  cv::warpPerspective(
      ref, other, H, ref.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(128));

  const auto fRef = extract(GetParam().type, ref).subset(patch);
  const auto fOther = extract(GetParam().type, other);
  matching::CFeatureMatcher::TOptions mo;
  mo.matcher = GetParam().matcher;
  const auto matches = matching::CFeatureMatcher(mo).match(fRef, fOther);
  ASSERT_GE(matches.size(), 20u);

  const auto res =
      matching::CHomographyLocator().locate(fRef, patch, fOther, other.size(), matches);
  ASSERT_TRUE(res.has_value());
  const std::vector<cv::Point2f> corners = {
      {200.f, 150.f}, {440.f, 150.f}, {440.f, 330.f}, {200.f, 330.f}};
  std::vector<cv::Point2f> expected;
  cv::perspectiveTransform(corners, expected, H);
  for (std::size_t i = 0; i < 4; ++i)
    EXPECT_LT(cv::norm(res->corners[i] - expected[i]), 3.0) << "corner " << i;
  EXPECT_EQ(res->numMatches, static_cast<int>(matches.size()));
  EXPECT_LE(res->falseMatches, res->numMatches - static_cast<int>(res->inliers.size()));
}

INSTANTIATE_TEST_SUITE_P(
    AllExtractors, WarpedPatch,
    ::testing::Values(
        TWarpCase{EFeatureType::ORB, matching::EMatcherType::FLANN},
        TWarpCase{EFeatureType::ORB, matching::EMatcherType::BRUTE_FORCE},
        TWarpCase{EFeatureType::SIFT, matching::EMatcherType::FLANN},
        TWarpCase{EFeatureType::SIFT, matching::EMatcherType::BRUTE_FORCE},
        TWarpCase{EFeatureType::SURF, matching::EMatcherType::FLANN}));

TEST(CHomographyLocator, unrelatedImagesAreNotLocated)
{
  const cv::Rect patch(200, 150, 240, 180);
  const cv::Mat a = sceneWithPatch(patch, 1);
  const cv::Mat b = sceneWithPatch(cv::Rect(100, 100, 240, 180), 2);
  const auto fa = extract(EFeatureType::ORB, a).subset(patch);
  const auto fb = extract(EFeatureType::ORB, b);
  matching::CFeatureMatcher::TOptions mo;
  mo.ratio = 1.0;  // let everything through: RANSAC must reject it
  const auto matches = matching::CFeatureMatcher(mo).match(fa, fb);
  EXPECT_FALSE(matching::CHomographyLocator().locate(fa, patch, fb, b.size(), matches).has_value());
}

TEST(CHomographyLocator, countsMatchesOutsideTheLocatedRoiAsFalse)
{
  // Identity mapping; three extra matches point far outside the ROI.
  features::TFeatureSet ref, other;
  ref.type = other.type = EFeatureType::ORB;
  std::vector<cv::DMatch> matches;
  for (int i = 0; i < 30; ++i)
  {
    const cv::Point2f p(110.f + 7 * (i % 6), 110.f + 11 * (i / 6));
    ref.keypoints.emplace_back(p, 7.f);
    other.keypoints.emplace_back(p, 7.f);
    matches.emplace_back(i, i, 0.f);
  }
  for (int i = 0; i < 3; ++i)
  {
    ref.keypoints.emplace_back(cv::Point2f(120.f + i, 120.f), 7.f);
    other.keypoints.emplace_back(cv::Point2f(500.f + 20 * i, 400.f), 7.f);
    matches.emplace_back(30 + i, 30 + i, 0.f);
  }
  const auto res = matching::CHomographyLocator().locate(
      ref, cv::Rect(100, 100, 60, 70), other, cv::Size(640, 480), matches);
  ASSERT_TRUE(res.has_value());
  EXPECT_EQ(res->falseMatches, 3);
  EXPECT_EQ(res->inliers.size(), 30u);
  EXPECT_NEAR(res->corners[0].x, 100, 0.5);
  EXPECT_NEAR(res->corners[2].y, 170, 0.5);
}

TEST(CFeatureMatcherOptions, iniErrorsNameSectionAndKey)
{
  mrpt::config::CConfigFileMemory cfg;
  cfg.write("FeatureMatcher", "matcher", "annoy");
  matching::CFeatureMatcher::TOptions o;
  try
  {
    o.loadFromConfigFile(cfg, "FeatureMatcher");
    FAIL();
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("[FeatureMatcher] matcher"), std::string::npos);
  }
  cfg.write("FeatureMatcher", "matcher", "flann");
  cfg.write("FeatureMatcher", "ratio", 1.5);
  EXPECT_THROW(o.loadFromConfigFile(cfg, "FeatureMatcher"), std::invalid_argument);
  mrpt::config::CConfigFileMemory h;
  h.write("HomographyLocator", "min_inliers", 2);
  matching::CHomographyLocator::TOptions ho;
  EXPECT_THROW(ho.loadFromConfigFile(h, "HomographyLocator"), std::invalid_argument);
}

TEST(CFeatureIndex, matchesLikeTheMatcherForEveryTypeAndRepeatedQueries)
{
  const cv::Mat a = sceneWithPatch(cv::Rect(200, 150, 200, 150), 3);
  cv::Mat b;
  cv::warpAffine(
      a, b, cv::getRotationMatrix2D(cv::Point2f(320, 240), 8.0, 1.05), a.size(), cv::INTER_LINEAR);
  for (auto t : {EFeatureType::SIFT, EFeatureType::SURF, EFeatureType::ORB})
    for (auto m : {matching::EMatcherType::FLANN, matching::EMatcherType::BRUTE_FORCE})
    {
      const auto fa = extract(t, a);
      const auto fb = extract(t, b);
      matching::CFeatureMatcher::TOptions o;
      o.matcher = m;
      // With the mutual check: its reverse FLANN index over the query is
      // seeded like the forward one, so a second query keeps the same
      // matches (before stop 38 it was not, and differed).
      o.cross_check = true;
      const matching::CFeatureIndex index(o, fb);
      EXPECT_EQ(index.size(), fb.size());
      const auto once = index.match(fa);
      ASSERT_GT(once.size(), 20u) << features::toString(t);
      // The index is reusable: a second query gives the same matches.
      expectSameMatches(index.match(fa), once);
      if (m == matching::EMatcherType::BRUTE_FORCE)
      {
        // Exact search: identical to a one-off match.
        const auto direct = matching::CFeatureMatcher(o).match(fa, fb);
        ASSERT_EQ(direct.size(), once.size());
        for (std::size_t i = 0; i < once.size(); ++i)
          EXPECT_EQ(direct[i].trainIdx, once[i].trainIdx);
      }
      EXPECT_TRUE(matching::CFeatureIndex(o, features::TFeatureSet()).match(fa).empty());
      EXPECT_THROW(
          index.match(extract(t == EFeatureType::ORB ? EFeatureType::SIFT : EFeatureType::ORB, a)),
          std::invalid_argument);
    }
}

TEST(CFeatureIndex, flannIndexDoesNotDependOnTheThreadsRandomState)
{
  // FLANN builds its kd-trees from cv::theRNG(): the index must be the same
  // whatever ran before on the thread (one seed per build), and the thread's
  // generator must be left as it was. Descriptors: 3000 random 64-D rows;
  // queries: 400 of them with noise, so the approximate search has to
  // choose among close neighbours.
  cv::RNG data(42);
  features::TFeatureSet train, query;
  train.type = query.type = features::EFeatureType::SURF;
  train.descriptors.create(3000, 64, CV_32F);
  data.fill(train.descriptors, cv::RNG::UNIFORM, 0.0, 1.0);
  train.keypoints.resize(3000);
  query.descriptors = train.descriptors.rowRange(0, 400).clone();
  cv::Mat noise(query.descriptors.size(), CV_32F);
  data.fill(noise, cv::RNG::NORMAL, 0.0, 0.15);
  query.descriptors += noise;
  query.keypoints.resize(400);

  matching::CFeatureMatcher::TOptions o;
  o.matcher = matching::EMatcherType::FLANN;
  std::vector<std::vector<cv::DMatch>> results;
  for (uint64_t state : {1ull, 2ull, 0xdeadbeefull})
  {
    cv::theRNG() = cv::RNG(state);
    const matching::CFeatureIndex index(o, train);
    EXPECT_EQ(cv::theRNG().state, state) << "the thread's generator was advanced";
    results.push_back(index.match(query));
  }
  ASSERT_GT(results.front().size(), 50u);
  for (std::size_t r = 1; r < results.size(); ++r)
    expectSameMatches(results[r], results.front());
}
