/* CFeatureIndex is safe to query from several threads at once (the SLAM
 * front end and the landmark database share keyframe and vote indexes):
 * concurrent queries give what sequential ones give, for FLANN (queries take
 * turns on the trained index) and brute force (no shared search state). Run
 * under ThreadSanitizer, this is the test that shows the index race-free. */
#include <gtest/gtest.h>
#include <roislam/features/CFeatureExtractor.h>
#include <roislam/matching/CFeatureIndex.h>

#include <opencv2/imgproc.hpp>
#include <thread>
#include <vector>

using namespace roislam;

namespace
{
features::TFeatureSet orbOf(const cv::Mat& img)
{
  features::CFeatureExtractor::TOptions o;
  o.feature_type = features::EFeatureType::ORB;
  o.max_features = 800;
  return features::CFeatureExtractor(o).extract(img);
}

bool same(const std::vector<cv::DMatch>& a, const std::vector<cv::DMatch>& b)
{
  if (a.size() != b.size())
    return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].queryIdx != b[i].queryIdx || a[i].trainIdx != b[i].trainIdx)
      return false;
  return true;
}
}  // namespace

TEST(CFeatureIndex, ConcurrentQueriesMatchSequentialOnes)
{
  cv::Mat train(480, 640, CV_8UC1);
  cv::randu(train, 0, 255);
  cv::GaussianBlur(train, train, cv::Size(5, 5), 1.5);
  std::vector<features::TFeatureSet> queries;
  for (double angle : {3.0, 6.0, 9.0, 12.0})
  {
    cv::Mat q;
    cv::warpAffine(
        train, q, cv::getRotationMatrix2D(cv::Point2f(320, 240), angle, 1.0), train.size());
    queries.push_back(orbOf(q));
  }
  const auto trainSet = orbOf(train);
  for (auto m : {matching::EMatcherType::FLANN, matching::EMatcherType::BRUTE_FORCE})
  {
    matching::CFeatureMatcher::TOptions o;
    o.matcher = m;
    const matching::CFeatureIndex index(o, trainSet);
    std::vector<std::vector<cv::DMatch>> expected;
    for (const auto& q : queries)
      expected.push_back(index.match(q));
    ASSERT_GT(expected.front().size(), 50u);
    std::vector<int> agree(queries.size() * 4, 0);
    std::vector<std::thread> threads;
    for (std::size_t t = 0; t < agree.size(); ++t)
      threads.emplace_back(
          [&, t]
          {
            const std::size_t k = t % queries.size();
            agree[t] = same(index.match(queries[k]), expected[k]) ? 1 : 0;
          });
    for (auto& th : threads)
      th.join();
    for (std::size_t t = 0; t < agree.size(); ++t)
      EXPECT_EQ(agree[t], 1) << "thread " << t << " matcher " << static_cast<int>(m);
  }
}
