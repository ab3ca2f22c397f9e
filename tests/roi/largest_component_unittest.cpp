/* largestComponent against OpenCV's connectedComponentsWithStats (8-connected):
 * same area and, when the largest component is unique, the same box; on
 * random masks of many densities and shapes (touching diagonals, borders,
 * runs longer than a word, non-255 foreground values) and, with the shared
 * data, on the detector's masks of real fr1 frames. */
#include <gtest/gtest.h>
#include <roislam/roi/CRoiDetector.h>
#include <roislam/roi/LargestComponent.h>
#include <roislam/testing/TestData.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <random>

using roislam::roi::largestComponent;

namespace
{
/** OpenCV's answer: area of the largest component, its box, and whether
 *  another component is as large. */
struct TReference
{
  int area = 0;
  cv::Rect box;
  bool unique = true;
};

TReference reference(const cv::Mat& mask)
{
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  TReference r;
  for (int l = 1; l < n; ++l)
  {
    const int a = stats.at<int>(l, cv::CC_STAT_AREA);
    if (a > r.area)
    {
      r.area = a;
      r.unique = true;
      r.box = cv::Rect(
          stats.at<int>(l, cv::CC_STAT_LEFT), stats.at<int>(l, cv::CC_STAT_TOP),
          stats.at<int>(l, cv::CC_STAT_WIDTH), stats.at<int>(l, cv::CC_STAT_HEIGHT));
    }
    else if (a == r.area)
      r.unique = false;
  }
  return r;
}

void expectSame(const cv::Mat& mask, const std::string& what)
{
  const auto ref = reference(mask);
  const auto ours = largestComponent(mask);
  if (ref.area == 0)
  {
    EXPECT_FALSE(ours.has_value()) << what;
    return;
  }
  ASSERT_TRUE(ours.has_value()) << what;
  EXPECT_EQ(ours->area, ref.area) << what;
  if (ref.unique)
  {
    EXPECT_EQ(ours->box, ref.box) << what;
  }
}
}  // namespace

TEST(LargestComponent, MatchesOpenCvOnRandomMasks)
{
  std::mt19937 rng(3);
  for (int trial = 0; trial < 300; ++trial)
  {
    const int rows = 1 + static_cast<int>(rng() % 90), cols = 1 + static_cast<int>(rng() % 130);
    cv::Mat noise(rows, cols, CV_8UC1);
    cv::randu(noise, 0, 256);
    const int threshold = static_cast<int>(rng() % 256);
    cv::Mat mask = noise > threshold;
    if (trial % 3 == 0)
    {
      // Blobs: grow the speckles, as stage 1's morphology does.
      cv::dilate(mask, mask, cv::Mat(), cv::Point(-1, -1), 1 + static_cast<int>(rng() % 3));
    }
    if (trial % 5 == 0)
      mask.setTo(7, mask);  // any non-zero value is foreground
    expectSame(mask, "trial " + std::to_string(trial));
  }
}

TEST(LargestComponent, DiagonalsBordersAndEmpty)
{
  cv::Mat m = cv::Mat::zeros(5, 20, CV_8UC1);
  EXPECT_FALSE(largestComponent(m).has_value());
  // A diagonal staircase is one 8-connected component of 5 pixels.
  for (int i = 0; i < 5; ++i)
    m.at<uchar>(i, i) = 255;
  auto c = largestComponent(m);
  ASSERT_TRUE(c.has_value());
  EXPECT_EQ(c->area, 5);
  EXPECT_EQ(c->box, cv::Rect(0, 0, 5, 5));
  // A full row longer than a machine word, touching both borders.
  cv::Mat row = cv::Mat::zeros(3, 37, CV_8UC1);
  row.row(2).setTo(255);
  c = largestComponent(row);
  ASSERT_TRUE(c.has_value());
  EXPECT_EQ(c->box, cv::Rect(0, 2, 37, 1));
  // Two equal components: the first in raster order.
  cv::Mat two = cv::Mat::zeros(6, 10, CV_8UC1);
  two(cv::Rect(6, 0, 2, 2)).setTo(255);
  two(cv::Rect(0, 3, 2, 2)).setTo(255);
  c = largestComponent(two);
  ASSERT_TRUE(c.has_value());
  EXPECT_EQ(c->box, cv::Rect(6, 0, 2, 2));
  EXPECT_THROW(largestComponent(cv::Mat::zeros(3, 3, CV_16UC1)), std::invalid_argument);
}

TEST(LargestComponent, MatchesOpenCvOnRealRoiMasks)
{
  ROISLAM_REQUIRE_SHARED_TUM(dir);
  std::vector<std::filesystem::path> images;
  for (const auto& e : std::filesystem::directory_iterator(dir + "/rgb"))
    images.push_back(e.path());
  std::sort(images.begin(), images.end());
  for (const auto& preset : {"small", "big"})
  {
    roislam::roi::CRoiDetector::TOptions o;
    o.setPreset(preset);
    const roislam::roi::CRoiDetector det(o);
    for (std::size_t i = 0; i < images.size(); i += 10)
      expectSame(
          det.foregroundMask(cv::imread(images[i].string())),
          std::string(preset) + " " + images[i].filename().string());
  }
}
