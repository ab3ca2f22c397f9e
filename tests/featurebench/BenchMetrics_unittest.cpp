/* Unit tests of the repeatability / matching-score metrics (BenchMetrics.h). */
#include <gtest/gtest.h>
#include <roislam/featurebench/BenchMetrics.h>
#include <roislam/featurebench/CFeatureBench.h>

#include <algorithm>
#include <opencv2/core.hpp>
#include <random>

using namespace roislam::featurebench;

namespace
{
struct TSet
{
  std::vector<cv::KeyPoint> kps;
  cv::Mat desc;
};

/** n keypoints on a jittered 25 px grid (at least 15 px apart, so a 3 px
 *  shift never lands on a neighbour) with random unit descriptors. */
TSet randomSet(int n, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> jitter(-5, 5);
  std::vector<cv::Point2f> cells;
  for (int y = 20; y <= 460; y += 25)
    for (int x = 20; x <= 620; x += 25)
      cells.emplace_back(static_cast<float>(x), static_cast<float>(y));
  std::shuffle(cells.begin(), cells.end(), rng);
  TSet s;
  s.desc.create(n, 16, CV_32F);
  cv::randn(s.desc, 0, 1);
  for (int i = 0; i < n; ++i)
  {
    s.kps.emplace_back(cells[i] + cv::Point2f(jitter(rng), jitter(rng)), 10.0f);
    s.desc.row(i) /= cv::norm(s.desc.row(i));
  }
  return s;
}

TSet mapSet(const TSet& a, const cv::Matx33d& H, double scale)
{
  TSet b = a;
  for (auto& k : b.kps)
  {
    const cv::Vec3d q = H * cv::Vec3d(k.pt.x, k.pt.y, 1);
    k.pt = cv::Point2f(static_cast<float>(q[0] / q[2]), static_cast<float>(q[1] / q[2]));
    k.size = static_cast<float>(k.size * scale);
  }
  return b;
}
}  // namespace

TEST(BenchMetrics, IdenticalSetsArePerfect)
{
  const TSet a = randomSet(200, 1);
  const auto m = evaluatePair(
      a.kps, a.desc, a.kps, a.desc, cv::Matx33d::eye(), {640, 480}, {640, 480}, cv::NORM_L2);
  EXPECT_EQ(m.commonA, 200u);
  EXPECT_EQ(m.correspondences, 200u);
  EXPECT_DOUBLE_EQ(m.repeatability, 1.0);
  EXPECT_DOUBLE_EQ(m.matchingScore, 1.0);
}

TEST(BenchMetrics, MappedSetUnderRotationIsPerfectAndShiftedIsNot)
{
  const cv::Size sz(640, 480);
  const TSet a = randomSet(150, 2);
  const cv::Matx33d H = CFeatureBench::homography("rot30", sz);
  const TSet b = mapSet(a, H, 1.0);
  auto m = evaluatePair(a.kps, a.desc, b.kps, b.desc, H, sz, sz, cv::NORM_L2);
  EXPECT_GT(m.commonA, 50u);
  EXPECT_EQ(m.correspondences, std::min(m.commonA, m.commonB));
  EXPECT_DOUBLE_EQ(m.repeatability, 1.0);
  EXPECT_DOUBLE_EQ(m.matchingScore, 1.0);

  // Every point displaced by 3 px (> 2.5 px tolerance): no correspondence.
  TSet shifted = b;
  for (auto& k : shifted.kps)
    k.pt += cv::Point2f(3.0f, 0.0f);
  m = evaluatePair(a.kps, a.desc, shifted.kps, shifted.desc, H, sz, sz, cv::NORM_L2);
  EXPECT_EQ(m.correspondences, 0u);
  EXPECT_EQ(m.correctMatches, 0u);
  // Displaced by 2 px: still a correspondence.
  for (auto& k : shifted.kps)
    k.pt -= cv::Point2f(1.0f, 0.0f);
  m = evaluatePair(a.kps, a.desc, shifted.kps, shifted.desc, H, sz, sz, cv::NORM_L2);
  EXPECT_DOUBLE_EQ(m.repeatability, 1.0);
}

TEST(BenchMetrics, ScaleMustAgreeWithTheHomography)
{
  const cv::Size sz(640, 480);
  const TSet a = randomSet(150, 3);
  const cv::Matx33d H = CFeatureBench::homography("scale1.5", sz);
  // Sizes scaled like the image: all correspond.
  auto m = evaluatePair(a.kps, a.desc, mapSet(a, H, 1.5).kps, a.desc, H, sz, sz, cv::NORM_L2);
  EXPECT_DOUBLE_EQ(m.repeatability, 1.0);
  // Sizes unchanged although the image was zoomed 1.5x: ratio 1.5 > 1.29.
  m = evaluatePair(a.kps, a.desc, mapSet(a, H, 1.0).kps, a.desc, H, sz, sz, cv::NORM_L2);
  EXPECT_EQ(m.correspondences, 0u);
  // Only the common part counts: a 1.5x zoom keeps the central 1/1.5 of A.
  m = evaluatePair(a.kps, a.desc, mapSet(a, H, 1.5).kps, a.desc, H, sz, sz, cv::NORM_L2);
  EXPECT_LT(m.commonA, 120u);
  EXPECT_GT(m.commonA, 30u);
}

TEST(BenchMetrics, WrongDescriptorsGiveRepeatabilityButNoMatches)
{
  const TSet a = randomSet(100, 4);
  TSet b;
  b.kps = a.kps;
  // Reverse descriptor rows: geometry intact, descriptors of other points.
  cv::flip(a.desc, b.desc, 0);
  const auto m = evaluatePair(
      a.kps, a.desc, b.kps, b.desc, cv::Matx33d::eye(), {640, 480}, {640, 480}, cv::NORM_L2);
  EXPECT_DOUBLE_EQ(m.repeatability, 1.0);
  EXPECT_LT(m.matchingScore, 0.05);
}

TEST(BenchMetrics, OneToOneCorrespondences)
{
  // Two keypoints of B near one of A: one correspondence, not two.
  std::vector<cv::KeyPoint> a{cv::KeyPoint(100, 100, 10)};
  std::vector<cv::KeyPoint> b{cv::KeyPoint(101, 100, 10), cv::KeyPoint(100, 101, 10)};
  const auto m = evaluatePair(
      a, cv::Mat(), b, cv::Mat(), cv::Matx33d::eye(), {640, 480}, {640, 480}, cv::NORM_L2);
  EXPECT_EQ(m.correspondences, 1u);
  EXPECT_DOUBLE_EQ(m.repeatability, 1.0);  // min(1, 2) = 1
  EXPECT_EQ(m.matchingScore, 0.0);         // no descriptors
}

TEST(BenchMetrics, EmptyAndInconsistentInputs)
{
  const TSet a = randomSet(10, 5);
  const auto m = evaluatePair(
      a.kps, a.desc, {}, cv::Mat(), cv::Matx33d::eye(), {640, 480}, {640, 480}, cv::NORM_L2);
  EXPECT_EQ(m.repeatability, 0.0);
  EXPECT_THROW(
      evaluatePair(
          a.kps, a.desc.rowRange(0, 5), a.kps, a.desc, cv::Matx33d::eye(), {640, 480}, {640, 480},
          cv::NORM_L2),
      std::invalid_argument);
}

TEST(BenchMetrics, LocalisationSigmaIsOneKeypointsNoise)
{
  EXPECT_DOUBLE_EQ(localisationSigma({}), 0.0);
  // Pairs of keypoints each displaced by N(0, 0.3^2) per axis: their
  // difference has sigma 0.3 sqrt 2; the estimate gives back 0.3.
  std::mt19937 rng(11);
  std::normal_distribution<double> n(0, 0.3);
  std::vector<double> e;
  for (int i = 0; i < 20000; ++i)
    e.push_back(n(rng) - n(rng));
  EXPECT_NEAR(localisationSigma(e), 0.3, 0.01);
  // Robust: a tenth of gross errors barely moves it.
  for (int i = 0; i < 2000; ++i)
    e.push_back(i % 2 ? 2.0 : -2.0);
  EXPECT_NEAR(localisationSigma(e), 0.3, 0.04);
}

TEST(BenchMetrics, FinestScaleErrorsAreTheCorrectMatchesOffsets)
{
  // B is A shifted by (0.25, -0.5) px with H the identity: every correct
  // match of the finest scale reads that offset; keypoints twice the
  // finest size are left out.
  TSet a = randomSet(100, 12);
  for (std::size_t i = 0; i < a.kps.size(); i += 2)
    a.kps[i].size = 20.0f;
  TSet b = a;
  for (auto& k : b.kps)
    k.pt += cv::Point2f(0.25f, -0.5f);
  const auto m = evaluatePair(
      a.kps, a.desc, b.kps, b.desc, cv::Matx33d::eye(), {640, 480}, {640, 480}, cv::NORM_L2);
  EXPECT_EQ(m.correctMatches, 100u);
  ASSERT_EQ(m.finestScaleErrors.size(), 2u * 50u);
  for (std::size_t i = 0; i < m.finestScaleErrors.size(); i += 2)
  {
    EXPECT_NEAR(m.finestScaleErrors[i], 0.25, 1e-4);
    EXPECT_NEAR(m.finestScaleErrors[i + 1], -0.5, 1e-4);
  }
  // Not collected when the caller does not want them; the counts are the same.
  const auto n = evaluatePair(
      a.kps, a.desc, b.kps, b.desc, cv::Matx33d::eye(), {640, 480}, {640, 480}, cv::NORM_L2,
      TCorrespondenceCriterion(), false);
  EXPECT_EQ(n.correctMatches, 100u);
  EXPECT_TRUE(n.finestScaleErrors.empty());
}
