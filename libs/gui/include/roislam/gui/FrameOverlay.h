/* The live view's pictures of the current frame, drawn with OpenCV on the
 * drawing thread: the colour image with what the front end did on it (the
 * ROI box in yellow, the tracking region in cyan, the features in two
 * colours: green where the frame was tracked (inside the ROI / region in
 * ROI modes, all of them in traditional mode), orange for the rest of the
 * image (the extension), and a caption with the tracking method, red when
 * it fell back), and the depth image in false colour. Called by CLiveView.
 */
#pragma once

#include <roislam/gui/TLiveFrame.h>

#include <opencv2/core.hpp>

namespace roislam::gui
{
/** BGR colours of the overlay, so that tests and the legend agree. */
struct TOverlayColours
{
  static cv::Scalar roiBox() { return {0, 230, 255}; }
  static cv::Scalar region() { return {255, 230, 0}; }
  static cv::Scalar tracked() { return {40, 220, 40}; }
  static cv::Scalar extension() { return {0, 140, 255}; }
  static cv::Scalar fallback() { return {40, 40, 255}; }
};

/** A feature at `pixel` counts as tracked (green) in this frame: inside the
 *  tracking region (or the ROI when there is none) in ROI modes, always in
 *  traditional mode. */
bool isTrackedFeature(const TLiveFrame& frame, const cv::Point2f& pixel, bool roiMode);

/** The colour image (BGR, a copy) with ROI, region, features and caption. */
cv::Mat drawFrameOverlay(const TLiveFrame& frame, bool roiMode);

/** Depth in metres as a false-colour BGR image (near blue, far red up to
 *  maxDepthM; no reading black). */
cv::Mat colouriseDepth(const cv::Mat& depth, double maxDepthM);
}  // namespace roislam::gui
