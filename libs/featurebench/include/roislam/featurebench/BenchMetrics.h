/* Repeatability and matching score of two keypoint sets related by a known
 * homography (Mikolajczyk & Schmid, "A performance evaluation of local
 * descriptors", PAMI 2005), with the simpler documented correspondence
 * criterion below instead of ellipse overlap. Used by CFeatureBench.
 */
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/core/types.hpp>
#include <vector>

namespace roislam::featurebench
{
struct TCorrespondenceCriterion
{
  /** A keypoint a of image A and b of image B correspond when H(a) lies within
   *  this distance of b (pixels in B) ... */
  double pixelTolerance = 2.5;
  /** ... and their sizes agree after the local scale of H: size_b / (k size_a)
   *  in [1/r, r]. r = 1/sqrt(0.6) ~ 1.29: two concentric circles whose radii
   *  differ by this ratio overlap by 60 % (the region overlap criterion). */
  double maxScaleRatio = 1.2910;
  /** Keypoints count as "in the common part" when they map inside the other
   *  image at least this far from its border (pixels), so that features on
   *  the black border of a warped image are not counted. */
  double borderMargin = 8.0;
};

struct TPairMetrics
{
  /** Keypoints of A (resp. B) in the part both images show. */
  std::size_t commonA = 0, commonB = 0;
  /** One-to-one geometric correspondences (greedy by distance). */
  std::size_t correspondences = 0;
  /** Keypoints of A (common part) whose descriptor nearest neighbour among
   *  B's common keypoints is a geometric correspondence. */
  std::size_t correctMatches = 0;
  /** correspondences / min(commonA, commonB); 0 when a set is empty. */
  double repeatability = 0;
  /** correctMatches / min(commonA, commonB); 0 when a set is empty. */
  double matchingScore = 0;
};

/** H maps pixel coordinates of A (size sizeA) to B (size sizeB); 3x3 CV_64F.
 *  Descriptors (one row per keypoint) may be empty: the matching score is then
 *  0. normType: cv::NORM_L2 or cv::NORM_HAMMING. Throws std::invalid_argument
 *  on inconsistent sizes. */
TPairMetrics evaluatePair(
    const std::vector<cv::KeyPoint>& kpsA, const cv::Mat& descA,
    const std::vector<cv::KeyPoint>& kpsB, const cv::Mat& descB, const cv::Matx33d& H,
    const cv::Size& sizeA, const cv::Size& sizeB, int normType,
    const TCorrespondenceCriterion& criterion = TCorrespondenceCriterion());
}  // namespace roislam::featurebench
