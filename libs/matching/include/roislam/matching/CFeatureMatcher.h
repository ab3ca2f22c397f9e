/* Stage 3, first half: descriptor matching with Lowe's ratio test.
 * FLANN kd-tree for float descriptors (SIFT/SURF), FLANN LSH for binary ones
 * (ORB), or brute force (L2 / Hamming). Used by the landmark pipeline and the
 * SLAM front end.
 */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <roislam/features/TFeatureSet.h>

#include <opencv2/core/types.hpp>
#include <vector>

namespace roislam::matching
{
enum class EMatcherType
{
  FLANN,
  BRUTE_FORCE
};

class CFeatureMatcher
{
 public:
  /** ini section (default "FeatureMatcher"):
   *  - matcher       flann|brute_force  (default flann)
   *  - ratio         Lowe ratio in (0,1] (default 0.8)
   *  - cross_check   bool: keep only mutual best matches (default false)
   */
  struct TOptions : public mrpt::config::CLoadableOptions
  {
    EMatcherType matcher = EMatcherType::FLANN;
    double ratio = 0.8;
    bool cross_check = false;

    void loadFromConfigFile(
        const mrpt::config::CConfigFileBase& source, const std::string& section) override;
    void saveToConfigFile(
        mrpt::config::CConfigFileBase& target, const std::string& section) const override;
  };

  // Two constructors rather than a default argument: GCC rejects TOptions()
  // as a default argument inside the enclosing class.
  CFeatureMatcher();
  explicit CFeatureMatcher(const TOptions& options);

  /** Matches query against train; DMatch.queryIdx indexes query, trainIdx
   *  train. Both sets must be of the same feature type. Empty sets give no
   *  matches. */
  std::vector<cv::DMatch> match(
      const features::TFeatureSet& query, const features::TFeatureSet& train) const;

  const TOptions& options() const { return m_options; }

 private:
  TOptions m_options;
};
}  // namespace roislam::matching
