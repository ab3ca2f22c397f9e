/* A keyframe stored by the front end (CRgbdOdometry): its features with their
 * 3-D points, computed once when the keyframe is created and reused for every
 * later match (tracking, keyframe constraints, loop-closure verification by
 * the back end).
 */
#pragma once

#include <mrpt/math/TPoint3D.h>
#include <mrpt/poses/CPose3D.h>
#include <roislam/features/TFeatureSet.h>
#include <roislam/matching/CFeatureIndex.h>

#include <cstddef>
#include <memory>
#include <opencv2/core/types.hpp>
#include <optional>
#include <vector>

namespace roislam::frontend
{
struct TKeyframe
{
  /** 0-based, consecutive: keyframes()[id].id == id. */
  std::size_t id = 0;
  /** TRGBDFrame::index and ::timestamp of the frame. */
  std::size_t frameIndex = 0;
  double timestamp = 0;
  /** World pose; replaced by correctKeyframePoses() when the back end optimises. */
  mrpt::poses::CPose3D pose;

  /** Features stored for matching, only those with valid depth: the whole
   *  image's (default, TOptions::keyframe_full_features), else the set the
   *  frame was tracked with (ROI subset in ROI modes, whole image in
   *  traditional mode or after a fallback). Parallel to points and pixels. */
  features::TFeatureSet features;
  /** 3-D point of each feature in this keyframe's camera (optical) frame, m. */
  std::vector<mrpt::math::TPoint3D> points;
  /** Undistorted pixel coordinates of each feature (for reprojection). */
  std::vector<cv::Point2f> pixels;
  /** The camera's velocity when the frame was taken, in its own optical
   *  frame: angular (rad/s) and linear (m/s), as the front end estimated it
   *  for the frame's rolling-shutter correction (zero when unknown). It
   *  says how fast each keypoint moved in the image, which widens its noise
   *  (TOptions::keypoint_time_sigma_ms, KeyframeRegistration.cpp). */
  mrpt::math::TVector3D angularRate{0, 0, 0}, linearRate{0, 0, 0};
  /** Search structure over features, kept only while the keyframe is one of
   *  the recent ones every frame is matched against (null otherwise: older
   *  keyframes are matched rarely, by loop closures, and the indexes of a
   *  long sequence would cost hundreds of MB). */
  std::shared_ptr<const matching::CFeatureIndex> index;
  /** The ROI of the frame (ROI modes), if one was found. */
  std::optional<cv::Rect> roi;
  /** ROI mode only: the frame itself was tracked with whole-image features. */
  bool fullImageFallback = false;
  /** ROI modes (roi_extraction = region): the tracking region of the frame,
   *  which the next frames follow (empty when none), and the median depth of
   *  its features, metres. */
  cv::Rect region;
  double regionDepth = 0;

  /** roi_extraction = flow: corners good to track (Shi-Tomasi) with valid
   *  depth, which later frames follow by optical flow instead of describing
   *  the image (FlowTracking.h): their (distorted) image positions, 3-D
   *  points in this keyframe's optical frame and undistorted pixels. */
  std::vector<cv::Point2f> anchorKeypoints;
  std::vector<mrpt::math::TPoint3D> anchorPoints;
  std::vector<cv::Point2f> anchorPixels;
};
}  // namespace roislam::frontend
