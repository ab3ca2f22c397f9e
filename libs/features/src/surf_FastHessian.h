/* Private to CSurf: the Fast-Hessian detector of Bay et al. (2008), section 3:
 * box-filter approximations of the second derivatives on an integral image,
 * a scale space of growing filter sizes organised in octaves, 3x3x3
 * non-maximum suppression and quadratic sub-pixel / sub-scale interpolation.
 */
#pragma once

#include <opencv2/core/types.hpp>
#include <vector>

#include "surf_Integral.h"

namespace roislam::features::surf
{
struct TFastHessianParams
{
  double threshold = 100;
  int nOctaves = 4;
  int nOctaveLayers = 3;
};

/** Side length of filter `layer` (0 .. nOctaveLayers+1) of octave `octave`.
 *  As in the paper (section 3.3): the first octave starts with the 9x9 filter
 *  (scale 1.2) and grows in steps of 6; every further octave doubles the step
 *  and the sampling interval, and starts so that its first searched layer
 *  follows the previous octave's last searched layer by one old step. With
 *  nOctaveLayers = 2 this is exactly the paper's 9,15,21,27 / 15,27,39,51 /
 *  27,51,75,99 / 51,99,147,195; any value gives odd filter sizes with odd lobes
 *  (so every filter is centred on a pixel) and no scale searched twice. */
int filterSize(int octave, int layer, int nOctaveLayers);

/** Scale (sigma of the approximated Gaussian) of a filter of side L. */
inline float filterScale(float L)
{
  return 1.2f * L / 9.0f;
}

/** Detects keypoints. KeyPoint.size = interpolated filter side L (OpenCV SURF's
 *  convention; the scale is 1.2 L / 9), response = interpolated normalised
 *  Hessian determinant, class_id = sign of the Laplacian (+1 / -1), octave =
 *  octave index, angle = -1 (assigned later). Order is deterministic. */
std::vector<cv::KeyPoint> detectFastHessian(
    const TIntegral& integral, const TFastHessianParams& params);

/** Sign of the Laplacian (trace of the box-filter Hessian) at a keypoint, at
 *  the filter size nearest to its size; used for provided keypoints. */
int laplacianSign(const TIntegral& integral, const cv::KeyPoint& kp);
}  // namespace roislam::features::surf
