/* Keypoints and descriptors of one image, as produced by CFeatureExtractor and
 * consumed by the matchers, the landmark database and the SLAM front end.
 */
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/core/types.hpp>
#include <string>
#include <vector>

namespace roislam::features
{
enum class EFeatureType
{
  SIFT,
  SURF,
  ORB
};

/** "sift" | "surf" | "orb" (case-insensitive); throws std::invalid_argument. */
EFeatureType featureTypeFromString(const std::string& s);
std::string toString(EFeatureType t);
/** ORB descriptors are binary (Hamming); SIFT/SURF are float (L2). */
inline bool isBinary(EFeatureType t)
{
  return t == EFeatureType::ORB;
}

/** A detector's keypoint noise at its finest detection scale (px per image
 *  axis, 1 sigma), as a registration between two frames sees it: ORB 0.72,
 *  SURF 0.46, SIFT 0.31 (how they were measured: TFeatureSet.cpp). It grows
 *  with the detection size (CRgbdOdometry's scale_aware_weights). A
 *  detector fact: what a camera adds (blur, compression, timing) is the
 *  sensor's TSensorDescription::keypoint_sigma_px, added in quadrature. */
double finestScaleSigmaPx(EFeatureType t);

struct TFeatureSet
{
  EFeatureType type = EFeatureType::ORB;
  std::vector<cv::KeyPoint> keypoints;
  /** One row per keypoint: CV_32F for SIFT/SURF, CV_8U for ORB. */
  cv::Mat descriptors;

  std::size_t size() const { return keypoints.size(); }
  bool empty() const { return keypoints.empty(); }
  /** The features whose keypoint lies inside rect (no re-extraction: stage 2
   *  extracts once per frame and the ROI selects from that set). */
  TFeatureSet subset(const cv::Rect& rect) const;
  /** The features at the given indices, in that order. */
  TFeatureSet select(const std::vector<int>& indices) const;
};

/** a's features followed by b's (same type; an empty set takes the other's). */
TFeatureSet concat(const TFeatureSet& a, const TFeatureSet& b);
}  // namespace roislam::features
