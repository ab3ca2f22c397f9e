/* A train feature set with its search structure (FLANN kd-trees or LSH
 * tables) built once, for matching many query sets against it: the landmark
 * database's vote over all stored descriptors, or one ROI against several
 * landmark candidates. CFeatureMatcher::match builds one per call, which is
 * what made database queries cost more than SIFT extraction itself.
 */
#pragma once

#include <roislam/features/TFeatureSet.h>
#include <roislam/matching/CFeatureMatcher.h>

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
  CFeatureMatcher::TOptions m_options;
  features::EFeatureType m_type;
  cv::Mat m_descriptors;
  /** knnMatch is not const in OpenCV, but searching does not change the index. */
  cv::Ptr<cv::DescriptorMatcher> m_index;
};
}  // namespace roislam::matching
