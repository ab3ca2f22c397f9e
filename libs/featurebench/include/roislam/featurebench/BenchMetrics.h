/* Repeatability and matching score of two keypoint sets related by a known
 * homography (Mikolajczyk & Schmid, "A performance evaluation of local
 * descriptors", PAMI 2005) under one of two correspondence criteria:
 *  - Overlap (Mikolajczyk, Tuytelaars, Schmid et al., "A comparison of affine
 *    region detectors", IJCV 2005): every keypoint is a circular region of
 *    radius regionRadiusPerSize * keypoint.size; the region of a (image A) is
 *    mapped into B by the local similarity of H (our transformations are
 *    similarities, so a circle stays a circle), both regions are scaled by the
 *    factor that gives the mapped reference region radius 30 px, and a and b
 *    correspond when the overlap error 1 - |intersection| / |union| (computed
 *    exactly for two circles) is below maxOverlapError (paper: 40 %). The
 *    tolerance thus grows with the keypoint scale. For exact circles the
 *    normalisation to 30 px leaves the ratio unchanged; it is kept so that the
 *    numbers are those of the paper's procedure.
 *  - Pixel (the bench's original, simpler criterion): H(a) within
 *    pixelTolerance px of b and sizes within maxScaleRatio after the local
 *    scale of H, whatever the keypoint scale.
 * Used by CFeatureBench, which reports both.
 */
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/core/types.hpp>
#include <vector>

namespace roislam::featurebench
{
struct TCorrespondenceCriterion
{
  enum class EMode
  {
    Pixel,
    Overlap
  };
  EMode mode = EMode::Pixel;
  /** Pixel mode: a keypoint a of image A and b of image B correspond when
   *  H(a) lies within this distance of b (pixels in B) ... */
  double pixelTolerance = 2.5;
  /** ... and their sizes agree after the local scale of H: size_b / (k size_a)
   *  in [1/r, r]. r = 1/sqrt(0.6) ~ 1.29: two concentric circles whose radii
   *  differ by this ratio overlap by 60 % (the region overlap criterion). */
  double maxScaleRatio = 1.2910;
  /** Overlap mode: largest overlap error of corresponding regions (0.4 in the
   *  IJCV 2005 paper). */
  double maxOverlapError = 0.4;
  /** Overlap mode: region radius = this * keypoint.size (pixels). Extractors
   *  report size in different units; CFeatureBench sets it per extractor so
   *  that the region is the same multiple of the detection scale for all. */
  double regionRadiusPerSize = 0.5;
  /** Overlap mode: radius the mapped reference region is normalised to (px). */
  double normalisedRadius = 30.0;
  /** Keypoints count as "in the common part" when they map inside the other
   *  image at least this far from its border (pixels), so that features on
   *  the black border of a warped image are not counted. */
  double borderMargin = 8.0;
};

/** Overlap error 1 - |A n B| / |A u B| of two discs of radii r1, r2 whose
 *  centres are d apart (exact; 1 when disjoint). */
double circleOverlapError(double r1, double r2, double d);

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
  /** Where the correct matches of the finest detection scale lie against
   *  the homography: both components of b - H(a) (px in B) of each correct
   *  match whose two keypoints are within kFinestScaleRatio of the smallest
   *  keypoint.size of their image (keypoints without a size count as the
   *  finest). localisationSigma() makes them a keypoint noise. */
  std::vector<double> finestScaleErrors;
};

/** Keypoints up to this ratio above their image's smallest size count as
 *  detected at the finest scale (ORB's level 0 and 1 at factor 1.2; SIFT's
 *  and SURF's first octave's lower half). */
constexpr double kFinestScaleRatio = 1.5;

/** One keypoint's noise per image axis (px, 1 sigma) from errors of pairs of
 *  keypoints (each pair's difference carries two keypoints' noise): the
 *  robust standard deviation 1.4826 median|e| / sqrt(2); 0 when empty. */
double localisationSigma(std::vector<double> errors);

/** H maps pixel coordinates of A (size sizeA) to B (size sizeB); 3x3 CV_64F.
 *  Descriptors (one row per keypoint) may be empty: the matching score is then
 *  0. normType: cv::NORM_L2 or cv::NORM_HAMMING. finestScaleErrors: whether
 *  to collect TPairMetrics::finestScaleErrors (a caller evaluating the same
 *  pair under a second criterion needs them once). Throws
 *  std::invalid_argument on inconsistent sizes. */
TPairMetrics evaluatePair(
    const std::vector<cv::KeyPoint>& kpsA, const cv::Mat& descA,
    const std::vector<cv::KeyPoint>& kpsB, const cv::Mat& descB, const cv::Matx33d& H,
    const cv::Size& sizeA, const cv::Size& sizeB, int normType,
    const TCorrespondenceCriterion& criterion = TCorrespondenceCriterion(),
    bool finestScaleErrors = true);
}  // namespace roislam::featurebench
