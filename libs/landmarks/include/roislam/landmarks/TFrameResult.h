/* What the ROI landmark pipeline did with one frame: the dissertation's
 * per-frame log record. Produced by CRoiLandmarkTracker, written to
 * frames.csv by CRoiLandmarksApp and converted to a bearing-range observation
 * by CObservationProcessor.
 */
#pragma once

#include <mrpt/math/TPoint3D.h>

#include <opencv2/core/types.hpp>

#include <cstdint>
#include <optional>
#include <string>

namespace roislam::landmarks
{
enum class ERoiStatus
{
  /** No ROI detected ("NaN" in the dissertation's log). */
  NoRoi,
  /** A ROI was detected but not re-found in the adjacent frame ("no new ROI"). */
  NotConfirmed,
  /** A confirmed ROI, recalled as or stored as a landmark ("landmark k"). */
  Landmark
};

struct TFrameResult
{
  uint64_t frame = 0;
  double timestamp = 0;
  ERoiStatus status = ERoiStatus::NoRoi;
  /** The detected ROI box, when any. */
  std::optional<cv::Rect> roi;
  /** Recalled or new landmark (status Landmark), else -1. */
  int32_t landmarkId = -1;
  bool newLandmark = false;
  /** Confirmation: matches between the ROI and the previous frame, and those
   *  landing outside the located ROI. */
  int matches = 0;
  int falseMatches = 0;
  /** Database query: homography inliers of the recall, verified candidates. */
  int recallInliers = 0;
  int candidates = 0;
  /** Features of the whole frame and of the ROI. */
  int features = 0;
  int roiFeatures = 0;
  /** ROI features with depth, their mean/median depth (m; NaN when none). */
  int depthValid = 0;
  double depthMean = 0;
  double depthMedian = 0;
  /** ROI position in the optical camera frame, when depth allowed it. */
  std::optional<mrpt::math::TPoint3D> roiPosition;
  /** Processing time of this frame (pipeline only, no I/O), seconds. */
  double seconds = 0;

  /** "landmark k" / "no new ROI" / "NaN", as in the dissertation's log. */
  std::string statusText() const;
};
}  // namespace roislam::landmarks
