/* A frame made ready for the front end's tracking (CRgbdOdometry::prepare):
 * the frame, checked, its grey image and, in ROI modes, its ROI (stage 1).
 * prepare() is const and may run on another thread than process(), e.g. on
 * the thread that decodes the next frame (CSlamPipeline), so that stage 1
 * costs the tracking thread nothing.
 */
#pragma once

#include <roislam/io/TRGBDFrame.h>
#include <roislam/roi/CRoiDetector.h>

#include <optional>
#include <vector>

namespace roislam::frontend
{
struct TPreparedFrame
{
  io::TRGBDFrame frame;
  /** frame.rgb converted once, for the ROI detector and the features. */
  cv::Mat grey;
  /** Stage 1 ran on this frame (ROI modes; traditional mode runs it only
   *  for the frames that become keyframes, see CRgbdOdometry.h). */
  bool roiDetected = false;
  /** Its result: nullopt when no ROI was found (or not detected). */
  std::optional<roi::TRoi> roi;
  /** roi_extraction = flow: the grey image's optical-flow pyramid (from
   *  the image halved until under 1280 px wide: FlowTracking.h flowShift),
   *  built here so that it too runs ahead of the tracking thread. */
  std::vector<cv::Mat> flowPyramid;
  /** grey at the features' working resolution (feature_resolution,
   *  TRgbdOdometryOptions.h): grey halved featureShift times (grey itself at 0).
   *  Empty in a frame prepared elsewhere: process() then makes it. */
  cv::Mat featureGrey;
  int featureShift = 0;
  /** Time stage 1 took, and all of prepare() (grey image + stage 1), ms. */
  double roi_ms = 0, prepare_ms = 0;
};
}  // namespace roislam::frontend
