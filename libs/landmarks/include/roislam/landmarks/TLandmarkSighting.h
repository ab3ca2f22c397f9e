/* One sighting of a landmark (the frame in which a confirmed ROI was stored as
 * or recalled as that landmark). Kept by CLandmark, filled by CRoiLandmarkTracker.
 */
#pragma once

#include <mrpt/math/TPoint3D.h>

#include <cstdint>
#include <opencv2/core/types.hpp>

namespace roislam::landmarks
{
struct TLandmarkSighting
{
  /** Index of the frame in its sequence. */
  uint64_t frame = 0;
  /** Colour timestamp of the frame, seconds. */
  double timestamp = 0;
  /** The ROI box in that frame, pixels. */
  cv::Rect box;
  /** Position of the ROI in the camera's optical frame (x right, y down,
   *  z forward), metres; valid only when hasPosition. */
  mrpt::math::TPoint3D position{0, 0, 0};
  bool hasPosition = false;
  /** Homography inliers of the recall (0 for the first sighting). */
  int inliers = 0;
};
}  // namespace roislam::landmarks
