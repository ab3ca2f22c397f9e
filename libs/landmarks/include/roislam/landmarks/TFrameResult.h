/* What the ROI landmark pipeline did with one frame: the dissertation's
 * per-frame log record. Produced by CRoiLandmarkTracker, written to
 * frames.csv by CRoiLandmarksApp and converted to a bearing-range observation
 * by CObservationProcessor.
 */
#pragma once

#include <mrpt/math/TPoint3D.h>

#include <cstdint>
#include <opencv2/core/types.hpp>
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
  /** [RoiDetector] verify_hue rejected the grey detector's ROI (roi is then
   *  empty and status NoRoi). */
  bool rejectedByHue = false;
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
  /** ROI position in the optical camera frame (component-wise median of
   *  the ROI features' 3-D points), when depth allowed it. */
  std::optional<mrpt::math::TPoint3D> roiPosition;
  /** Where the landmark itself is in this frame (optical frame). For a
   *  new landmark: the ROI box and roiPosition. For a recall: the landmark's
   *  first-sight box located here by the homography, and its stored position
   *  mapped into this frame by the rigid 3-D alignment of the homography
   *  inliers (first-sight points -> current points), i.e. an observation of
   *  the same physical point, whereas the detected ROI box may be bigger or
   *  smaller than the landmark; when too few inliers have depth, the median
   *  position of the features inside the located box. */
  std::optional<cv::Rect> landmarkBox;
  std::optional<mrpt::math::TPoint3D> landmarkPosition;
  /** Pairs kept by that alignment and their RMS residual (m; NaN if none). */
  int rigidInliers = 0;
  double rigidRms = 0;
  /** Processing time of this frame (pipeline only, no I/O), seconds: wall
   *  clock, and CPU time of the calling thread (OpenCV worker threads not
   *  included). */
  double seconds = 0;
  double cpuSeconds = 0;
  /** Wall time of the stages: ROI detection, feature extraction,
   *  confirmation, database query. */
  double secondsRoi = 0, secondsFeatures = 0, secondsConfirm = 0, secondsQuery = 0;

  /** "landmark k" / "no new ROI" / "NaN", as in the dissertation's log. */
  std::string statusText() const;
};
}  // namespace roislam::landmarks
