/* One RGB-D frame as every roislam stage consumes it, independent of where it
 * came from (TUM folder, rawlog, simulator). Produced by CFrameSource.
 */
#pragma once

#include <mrpt/img/TCamera.h>

#include <cstddef>
#include <opencv2/core/mat.hpp>
#include <string>

namespace roislam::io
{
struct TRGBDFrame
{
  /** 0-based position among the frames the source delivered. */
  std::size_t index = 0;
  /** Colour timestamp in seconds (TUM stamps; used for trajectories). */
  double timestamp = 0;
  /** Timestamp of the depth image associated with this colour image. */
  double depthTimestamp = 0;
  /** Colour image, CV_8UC3, BGR order (OpenCV convention). */
  cv::Mat rgb;
  /** Depth in metres, CV_32FC1, registered to the colour camera; 0 = no reading. */
  cv::Mat depth;
  /** Pinhole intrinsics of the colour camera (depth is registered to it). */
  mrpt::img::TCamera camera;
  /** Where the colour image came from (file path, or empty), for logs. */
  std::string rgbSource;

  /** Grey version of rgb (CV_8UC1), computed on call. */
  cv::Mat grey() const;
};
}  // namespace roislam::io
