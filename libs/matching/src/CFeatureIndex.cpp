#include "roislam/matching/CFeatureIndex.h"

#include <cstdint>
#include <opencv2/core.hpp>
#include <opencv2/flann.hpp>
#include <stdexcept>

#include "roislam/matching/HammingKnn.h"

namespace roislam::matching
{
namespace
{
constexpr uint64_t kIndexSeed = 0x5eed;

/** FLANN's matcher for the descriptor kind (brute force needs none: exact
 *  search goes through hammingKnn or cv::BFMatcher directly). */
cv::Ptr<cv::DescriptorMatcher> makeFlannMatcher(bool binary)
{
  if (binary)
    // Multi-probe LSH as recommended by FLANN for binary descriptors.
    return cv::makePtr<cv::FlannBasedMatcher>(
        cv::makePtr<cv::flann::LshIndexParams>(6, 12, 1), cv::makePtr<cv::flann::SearchParams>(32));
  return cv::makePtr<cv::FlannBasedMatcher>(
      cv::makePtr<cv::flann::KDTreeIndexParams>(4), cv::makePtr<cv::flann::SearchParams>(32));
}
}  // namespace

CFeatureIndex::CFeatureIndex(
    const CFeatureMatcher::TOptions& options, const features::TFeatureSet& train)
    : m_options(options), m_type(train.type), m_descriptors(train.descriptors)
{
  if (m_descriptors.empty() || m_options.matcher == EMatcherType::BRUTE_FORCE)
    return;
  m_flann = makeFlannMatcher(features::isBinary(m_type));
  m_flann->add(std::vector<cv::Mat>{m_descriptors});
  // FLANN's randomised kd-trees and LSH tables draw from the thread's
  // cv::theRNG(), whose state is whatever ran before on that thread: the
  // same frames then built other trees, and rarely gave other matches,
  // depending on the process's history (roi-graphslam and
  // roi-graphslam-engine, run one after the other in one test process,
  // disagreed by one loop closure). Each index is built from one seed, and
  // the thread's generator is left as it was.
  cv::RNG& rng = cv::theRNG();
  const cv::RNG before = rng;
  rng = cv::RNG(kIndexSeed);
  m_flann->train();
  rng = before;
}

std::vector<std::vector<cv::DMatch>> CFeatureIndex::knn2(const cv::Mat& query) const
{
  std::vector<std::vector<cv::DMatch>> knn;
  if (m_flann)
  {
    std::lock_guard<std::mutex> lock(m_flannMutex);
    m_flann->knnMatch(query, knn, 2);
  }
  else if (features::isBinary(m_type))
    knn = hammingKnn(query, m_descriptors, 2);
  else
    cv::BFMatcher(cv::NORM_L2).knnMatch(query, m_descriptors, knn, 2);
  return knn;
}

std::vector<cv::DMatch> CFeatureIndex::match(const features::TFeatureSet& query) const
{
  if (query.empty() || m_descriptors.empty())
    return {};
  if (query.type != m_type || query.descriptors.type() != m_descriptors.type() ||
      query.descriptors.cols != m_descriptors.cols)
    throw std::invalid_argument("CFeatureMatcher::match: feature sets of different types");

  const auto knn = knn2(query.descriptors);
  std::vector<cv::DMatch> fwd;
  fwd.reserve(knn.size());
  for (const auto& k : knn)
  {
    if (k.empty())
      continue;
    // A single candidate (tiny train set, or LSH finding one bucket) has no
    // second neighbour to compare with; it is kept only with ratio 1.
    if (k.size() == 1)
    {
      if (m_options.ratio >= 1.0)
        fwd.push_back(k[0]);
      continue;
    }
    if (k[0].distance <= m_options.ratio * k[1].distance)
      fwd.push_back(k[0]);
  }
  if (!m_options.cross_check)
    return fwd;

  // Mutual check: the train feature's own best match must be the query
  // feature. The reverse search goes through an index over the query built
  // like this one (for FLANN: seeded; a FlannBasedMatcher trained inside
  // knnMatch drew from the thread's generator, and the same query could
  // keep other matches on a second call).
  const auto back = CFeatureIndex(m_options, query).knn2(m_descriptors);
  std::vector<cv::DMatch> out;
  for (const auto& m : fwd)
  {
    const auto& b = back[static_cast<std::size_t>(m.trainIdx)];
    if (!b.empty() && b[0].trainIdx == m.queryIdx)
      out.push_back(m);
  }
  return out;
}
}  // namespace roislam::matching
