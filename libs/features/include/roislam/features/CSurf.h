/* SURF (Bay, Ess, Tuytelaars, Van Gool, "Speeded-Up Robust Features", CVIU
 * 110(3), 2008), implemented from the paper because Debian's OpenCV ships no
 * xfeatures2d. A cv::Feature2D so it is usable wherever SIFT and ORB are.
 * Parameters have OpenCV SURF's meaning and defaults. Created by
 * CFeatureExtractor (feature_type = surf) and by feature-bench.
 * Note: SURF may be patent-encumbered in some jurisdictions.
 *
 * Keypoints: pt in pixels (pixel centres at integers); size = side L of the
 * box filter (OpenCV SURF's convention; the scale is s = 1.2 L / 9; a Gaussian
 * blob of sigma is found at s ~= 0.7 sigma); angle in degrees [0, 360),
 * measured from +x towards +y (image axes), 0 when upright; response =
 * interpolated box-filter Hessian determinant normalised by the filter area
 * (what hessianThreshold is compared with); octave = Fast-Hessian octave;
 * class_id = sign of the Laplacian. Output order: strongest response first.
 * Grey CV_8UC1 input (BGR/BGRA converted); other depths throw.
 * Multi-threaded with cv::parallel_for_; results do not depend on threads.
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
    /** Threshold on the (normalised) Hessian determinant response, >= 0. */
    double hessianThreshold = 100;
    /** Octaves of filter sizes, 1..10 (octaves whose filters exceed the image
     *  are skipped). */
    int nOctaves = 4;
    /** Layers searched for maxima per octave, 1..20 (each octave has two more
     *  filters, above and below). */
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
   *  SURF did, so matchers can skip pairs of opposite sign. With
   *  useProvidedKeypoints (what compute() does), the given keypoints are kept,
   *  their size read with the convention above (L = 7.5 s), and their angle
   *  (unless upright) and class_id recomputed; mask is ignored then. */
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
