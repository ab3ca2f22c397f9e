/* SURF (Bay, Ess, Tuytelaars, Van Gool, "Speeded-Up Robust Features", CVIU
 * 110(3), 2008), implemented from the paper because Debian's OpenCV ships no
 * xfeatures2d. A cv::Feature2D so it is usable wherever SIFT and ORB are.
 * Parameters have OpenCV SURF's meaning and defaults.
 * Note: SURF may be patent-encumbered in some jurisdictions.
 */
#pragma once

#include <opencv2/features2d.hpp>

namespace roislam::features
{
class CSurf : public cv::Feature2D
{
 public:
  struct TParams
  {
    /** Threshold on the (normalised) Hessian determinant response. */
    double hessianThreshold = 100;
    int nOctaves = 4;
    int nOctaveLayers = 3;
    /** 128-D descriptor instead of 64-D. */
    bool extended = false;
    /** U-SURF: skip orientation assignment (angle 0). */
    bool upright = false;
    /** Keep at most this many keypoints, strongest first; 0 = all. */
    int maxFeatures = 0;
  };

  /** Throws std::invalid_argument on invalid parameters (message names it). */
  static cv::Ptr<CSurf> create(const TParams& params);
  /** Default parameters. (A separate overload rather than a default argument:
   *  GCC rejects `= TParams()` for a nested struct with member initialisers.) */
  static cv::Ptr<CSurf> create();
  explicit CSurf(const TParams& params);

  const TParams& params() const { return m_params; }

  /** keypoint.class_id holds the sign of the Laplacian (+1 / -1), as OpenCV's
   *  SURF did, so matchers can skip pairs of opposite sign. */
  void detectAndCompute(
      cv::InputArray image, cv::InputArray mask, std::vector<cv::KeyPoint>& keypoints,
      cv::OutputArray descriptors, bool useProvidedKeypoints = false) override;

  int descriptorSize() const override { return m_params.extended ? 128 : 64; }
  int descriptorType() const override { return CV_32F; }
  int defaultNorm() const override { return cv::NORM_L2; }
  cv::String getDefaultName() const override { return "roislam.SURF"; }

 private:
  TParams m_params;
};
}  // namespace roislam::features
