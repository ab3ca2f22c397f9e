/* A train feature set with its search structure (FLANN kd-trees or LSH
 * tables) built once, for matching many query sets against it: the landmark
 * database's vote over all stored descriptors, or one ROI against several
 * landmark candidates. CFeatureMatcher::match builds one per call, which is
 * what made database queries cost more than SIFT extraction itself.
 *
 * Thread safety: match() may be called from several threads at once. Brute
 * force keeps no search state (OpenCV's const knnMatch over the stored
 * descriptors); OpenCV's FLANN search is a non-const call on the trained
 * matcher, so FLANN queries take turns on a mutex.
 */
#pragma once

#include <roislam/features/TFeatureSet.h>
#include <roislam/matching/CFeatureMatcher.h>

#include <mutex>
#include <opencv2/core/types.hpp>
#include <opencv2/features2d.hpp>
#include <vector>

namespace roislam::matching
{
class CFeatureIndex
{
 public:
  /** Builds the index over train's descriptors (shared, not copied: do not
   *  modify them while the index lives). An empty set matches nothing. */
  CFeatureIndex(const CFeatureMatcher::TOptions& options, const features::TFeatureSet& train);

  /** Same semantics as CFeatureMatcher::match(query, train): DMatch.queryIdx
   *  indexes query, trainIdx the train set; ratio test and optional mutual
   *  check. Throws std::invalid_argument for a query of another type. */
  std::vector<cv::DMatch> match(const features::TFeatureSet& query) const;

  std::size_t size() const { return static_cast<std::size_t>(m_descriptors.rows); }

 private:
  /** The two nearest train descriptors of each query descriptor. */
  std::vector<std::vector<cv::DMatch>> knn2(const cv::Mat& query) const;

  CFeatureMatcher::TOptions m_options;
  features::EFeatureType m_type;
  cv::Mat m_descriptors;
  /** Trained FLANN matcher (null for brute force or an empty set); its
   *  knnMatch is not const in OpenCV, hence the mutex. */
  cv::Ptr<cv::DescriptorMatcher> m_flann;
  mutable std::mutex m_flannMutex;
};
}  // namespace roislam::matching
