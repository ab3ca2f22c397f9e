/* Edges of the hue channel, for the second (colour) stage-1 detector that
 * verifies the grey ROI (CRoiDetector, [RoiDetector] verify_hue).
 *
 * Hue is an angle: 179 and 0 (OpenCV's 8-bit hue, 2 degrees per unit) are
 * neighbours, so Canny on the hue image would see a strong false edge at the
 * wrap. Each pixel's hue becomes the unit vector (cos h, sin h); its Sobel
 * derivatives, combined over both components, give a gradient whose
 * magnitude for a step between hues h1 and h2 is 8 K sin(|h1 - h2| / 2) (K
 * the vector's integer scale), the same for every pair of hues the same
 * angle apart, whatever side of the wrap they are on. Canny's thresholds are
 * given as such hue steps in degrees.
 *
 * Hue is undefined for grey pixels and meaningless for dark ones (it comes
 * from differences between colour channels that noise dominates there): a
 * pixel has a reliable hue only with saturation >= minSaturation and value
 * >= minValue (HSV, both in [0, 1]). Derivatives are zeroed wherever the 3x3
 * Sobel window touches an unreliable pixel, so neither a grey region nor the
 * border between a coloured and a grey region makes hue edges (the grey
 * detector sees those). With 8-bit colour noise of about 2 levels, the hue of
 * a pixel at the defaults' limit (chroma S V = 0.05, 13 levels) scatters by
 * about 9 degrees, below the default low threshold of 20.
 */
#pragma once

#include <opencv2/core.hpp>

namespace roislam::roi
{
struct THueEdgeParams
{
  /** Canny hysteresis thresholds as hue steps, degrees (0 < low <= high <= 180). */
  double lowDeg = 20;
  double highDeg = 40;
  /** Reliable-hue limits, HSV saturation and value in [0, 1]. */
  double minSaturation = 0.25;
  double minValue = 0.2;
};

/** The hue edge mask (CV_8UC1, 255 = edge) of a BGR image (CV_8UC3; throws
 *  std::invalid_argument otherwise). */
cv::Mat hueEdges(const cv::Mat& bgr, const THueEdgeParams& params);

/** The reliable-hue mask (CV_8UC1, 255 = reliable) of a BGR image. */
cv::Mat reliableHueMask(const cv::Mat& bgr, const THueEdgeParams& params);
}  // namespace roislam::roi
