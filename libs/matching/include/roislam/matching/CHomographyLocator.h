/* Stage 3, second half: RANSAC homography between a reference image region
 * (the ROI) and another image; locates the ROI in the other image and counts
 * false matches (matched features that land outside the located ROI). Used by
 * the landmark pipeline (ROI re-finding and landmark recall).
 */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <roislam/features/TFeatureSet.h>

#include <opencv2/core.hpp>
#include <optional>
#include <vector>

namespace roislam::matching
{
struct THomographyResult
{
  /** 3x3 CV_64F, maps reference image points to the other image. */
  cv::Mat H;
  /** The reference ROI's corners (tl, tr, br, bl) mapped into the other image. */
  std::vector<cv::Point2f> corners;
  /** Axis-aligned bounding box of corners, clipped to the other image. */
  cv::Rect box;
  /** RANSAC inliers among the input matches. */
  std::vector<cv::DMatch> inliers;
  /** Input matches whose point in the other image lies outside the located ROI. */
  int falseMatches = 0;
  /** Number of input matches. */
  int numMatches = 0;
};

class CHomographyLocator
{
 public:
  /** ini section (default "HomographyLocator"):
   *  - ransac_reproj_threshold  px > 0            (default 3.0)
   *  - ransac_max_iters         int > 0           (default 2000)
   *  - ransac_confidence        (0,1)             (default 0.995)
   *  - min_inliers              int >= 4          (default 10)
   *  - min_inlier_ratio         [0,1]             (default 0.25)
   *  - max_scale_change         > 1: the located ROI area may be at most this
   *                             factor bigger or smaller (default 4)
   */
  struct TOptions : public mrpt::config::CLoadableOptions
  {
    double ransac_reproj_threshold = 3.0;
    int ransac_max_iters = 2000;
    double ransac_confidence = 0.995;
    int min_inliers = 10;
    double min_inlier_ratio = 0.25;
    double max_scale_change = 4.0;

    void loadFromConfigFile(
        const mrpt::config::CConfigFileBase& source, const std::string& section) override;
    void saveToConfigFile(
        mrpt::config::CConfigFileBase& target, const std::string& section) const override;
  };

  // Two constructors rather than a default argument: GCC rejects TOptions()
  // as a default argument inside the enclosing class.
  CHomographyLocator();
  explicit CHomographyLocator(const TOptions& options);

  /** reference: features of the reference image (matches' queryIdx);
   *  other: features of the other image (matches' trainIdx); refRoi: the ROI in
   *  the reference image; otherSize: size of the other image.
   *  Returns nullopt when no plausible homography is found (too few matches or
   *  inliers, degenerate or non-convex quadrilateral, implausible scale). */
  std::optional<THomographyResult> locate(
      const features::TFeatureSet& reference, const cv::Rect& refRoi,
      const features::TFeatureSet& other, const cv::Size& otherSize,
      const std::vector<cv::DMatch>& matches) const;

  const TOptions& options() const { return m_options; }

 private:
  TOptions m_options;
};
}  // namespace roislam::matching
