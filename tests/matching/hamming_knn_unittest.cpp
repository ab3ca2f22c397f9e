// hammingKnn against the reference it replaces, cv::BFMatcher(NORM_HAMMING):
// the same matches, distances and order, ties included.
#include <gtest/gtest.h>
#include <roislam/matching/HammingKnn.h>

#include <opencv2/features2d.hpp>

using roislam::matching::hammingKnn;

namespace
{
/** Random descriptors; with few distinct bytes, many pairs tie. */
cv::Mat randomDescriptors(int rows, int cols, int distinct, std::uint64_t seed)
{
  cv::Mat m(rows, cols, CV_8U);
  cv::RNG rng(seed);
  rng.fill(m, cv::RNG::UNIFORM, 0, distinct);
  return m;
}

void expectSameAsOpenCv(const cv::Mat& q, const cv::Mat& t, int k)
{
  std::vector<std::vector<cv::DMatch>> ref;
  cv::BFMatcher(cv::NORM_HAMMING).knnMatch(q, t, ref, k);
  const auto got = hammingKnn(q, t, k);
  ASSERT_EQ(got.size(), ref.size());
  for (std::size_t i = 0; i < ref.size(); ++i)
  {
    ASSERT_EQ(got[i].size(), ref[i].size()) << "query " << i;
    for (std::size_t s = 0; s < ref[i].size(); ++s)
    {
      EXPECT_EQ(got[i][s].queryIdx, ref[i][s].queryIdx);
      EXPECT_EQ(got[i][s].trainIdx, ref[i][s].trainIdx) << "query " << i << " rank " << s;
      EXPECT_EQ(got[i][s].distance, ref[i][s].distance);
      EXPECT_EQ(got[i][s].imgIdx, ref[i][s].imgIdx);
    }
  }
}
}  // namespace

TEST(HammingKnn, MatchesOpenCvOnOrbSizedDescriptors)
{
  const cv::Mat q = randomDescriptors(300, 32, 256, 1);
  const cv::Mat t = randomDescriptors(700, 32, 256, 2);
  for (int k : {1, 2, 3})
    expectSameAsOpenCv(q, t, k);
}

TEST(HammingKnn, BreaksTiesAsOpenCv)
{
  // Two byte values: distances crowd into a few values, so ranks tie often.
  const cv::Mat q = randomDescriptors(100, 8, 2, 3);
  cv::Mat t = randomDescriptors(200, 8, 2, 4);
  t.row(5).copyTo(t.row(150));  // exact duplicates too
  for (int k : {1, 2, 4})
    expectSameAsOpenCv(q, t, k);
}

TEST(HammingKnn, WidthsThatAreNotWholeWords)
{
  // AKAZE's 61 bytes, one byte, 9 bytes: the tail outside 64-bit words.
  for (int cols : {61, 1, 9})
    expectSameAsOpenCv(
        randomDescriptors(50, cols, 256, 10 + cols), randomDescriptors(80, cols, 256, 20 + cols),
        2);
}

TEST(HammingKnn, FewerTrainRowsThanK)
{
  expectSameAsOpenCv(randomDescriptors(10, 32, 256, 5), randomDescriptors(1, 32, 256, 6), 2);
  const auto got =
      hammingKnn(randomDescriptors(3, 32, 256, 5), randomDescriptors(1, 32, 256, 6), 2);
  ASSERT_EQ(got.size(), 3u);
  for (const auto& r : got)
    EXPECT_EQ(r.size(), 1u);
}

TEST(HammingKnn, EmptySetsGiveEmptyLists)
{
  const auto none = hammingKnn(randomDescriptors(4, 32, 256, 7), cv::Mat(), 2);
  ASSERT_EQ(none.size(), 4u);
  for (const auto& r : none)
    EXPECT_TRUE(r.empty());
  EXPECT_TRUE(hammingKnn(cv::Mat(), randomDescriptors(4, 32, 256, 7), 2).empty());
}

TEST(HammingKnn, RejectsBadInput)
{
  const cv::Mat a = randomDescriptors(4, 32, 256, 8);
  EXPECT_THROW(hammingKnn(a, randomDescriptors(4, 16, 256, 9), 2), std::invalid_argument);
  EXPECT_THROW(hammingKnn(a, cv::Mat(4, 8, CV_32F, cv::Scalar(0)), 2), std::invalid_argument);
  EXPECT_THROW(hammingKnn(a, a, 0), std::invalid_argument);
  EXPECT_THROW(
      hammingKnn(randomDescriptors(2, 600, 256, 1), randomDescriptors(2, 600, 256, 2), 1),
      std::invalid_argument);
}
