/* Private to CSurf: orientation assignment and the SURF descriptor (Bay et al.
 * 2008, section 4), from Haar wavelet responses on the integral image.
 */
#pragma once

#include <opencv2/core/types.hpp>

#include "surf_Integral.h"

namespace roislam::features::surf
{
/** Scale sigma of a keypoint whose size is a filter side (1.2 L / 9). */
inline float keypointScale(const cv::KeyPoint& kp)
{
  return 1.2f * kp.size / 9.0f;
}

/** Dominant orientation in degrees [0, 360), image axes (x right, y down):
 *  Haar responses (side 4s) at step s within radius 6s, Gaussian-weighted
 *  (sigma 2s), summed in a sliding window of pi/3; the longest sum wins. */
float dominantOrientation(const TIntegral& integral, const cv::KeyPoint& kp);

/** Writes the 64-D (or 128-D when extended) unit-length descriptor of kp into
 *  out. The 20s window is aligned with kp.angle (degrees), or with the image
 *  axes when upright. */
void describe(
    const TIntegral& integral, const cv::KeyPoint& kp, bool upright, bool extended, float* out);
}  // namespace roislam::features::surf
