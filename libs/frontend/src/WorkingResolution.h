/* The resolution the front end detects and describes features at
 * (feature_resolution, TRgbdOdometryOptions.h). A 1920 x 1080 camera has 6.75x the
 * pixels of a 640 x 480 one, and ORB / SIFT / SURF cost scales with the
 * pixels (a whole-image SIFT description took about 600 ms there, README
 * "Cameras wider than 1280 px"); halved, it still resolves the scene more
 * finely than a 640 x 480 camera. The rule is the optical flow's
 * (FlowTracking.h flowShift): halve until under 1280 px wide, so 640 x 480
 * and 960 x 540 cameras keep their own resolution, bit for bit.
 * Keypoints always come back in the camera's pixels (pixel centres: u at the
 * working level is 2^s u + (2^s - 1) / 2), their sizes scaled with them. */
#pragma once

#include <roislam/features/CFeatureExtractor.h>

#include <cstddef>
#include <opencv2/core.hpp>
#include <vector>

#include "FlowTracking.h"

namespace roislam::frontend::detail
{
/** Halvings from the camera's resolution to the features' working one:
 *  flowShift(image) when `automatic`, else 0. */
int featureShift(const cv::Size& image, bool automatic);

/** grey halved `shift` times (pyrDown, as the flow's pyramid); grey itself
 *  (no copy) for 0. */
cv::Mat reduced(const cv::Mat& grey, int shift);

/** The image at the working resolution and its shift. */
struct TWorkingImage
{
  cv::Mat grey;
  int shift = 0;
  /** The camera's image size. */
  cv::Size image;
};

/** grey at the working resolution feature_resolution asks for (`automatic`:
 *  auto): featureShift and reduced together. */
TWorkingImage workingImage(const cv::Mat& grey, bool automatic);

/** The flow's pyramid of `grey` (FlowTracking.h flowPyramid), built from
 *  the working image when the flow tracks at its resolution (one pyrDown
 *  less). */
std::vector<cv::Mat> flowPyramidOf(
    const cv::Mat& grey, const TWorkingImage& w, const TFlowParams& p, bool withDerivatives);

/** Keypoints (and sizes) of `set`, found at the working level `shift`, in
 *  the camera's pixels. */
void toImagePixels(features::TFeatureSet& set, int shift);

/** `r` (camera pixels) in an image scaled by `scale`, rounded outwards so
 *  that it covers every pixel r touches there. */
cv::Rect scaledOutwards(const cv::Rect& r, double scale);

/** CFeatureExtractor::extractIn at the working resolution: `region` (camera
 *  pixels) taken outwards there; only keypoints inside `region` come back,
 *  in camera pixels. `pixels`: the pixels the detector ran on (at its
 *  resolution: the work). */
features::TFeatureSet extractIn(
    const features::CFeatureExtractor& e, const TWorkingImage& w, const cv::Rect& region, int cap,
    std::size_t* pixels);
}  // namespace roislam::frontend::detail
