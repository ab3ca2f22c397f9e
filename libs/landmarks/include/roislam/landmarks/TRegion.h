/* A region of one frame to identify in the landmark database: a confirmed
 * ROI (CRoiLandmarkTracker, whose features and depth come from the frame) or
 * a keyframe's ROI (the SLAM back end, whose features were extracted by the
 * front end). Passed to CObservationProcessor::processRegion(), the one path
 * from a region to a landmark observation.
 */
#pragma once

#include <mrpt/img/TCamera.h>
#include <mrpt/math/TPoint3D.h>
#include <roislam/features/TFeatureSet.h>

#include <cstdint>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

namespace roislam::landmarks
{
struct TRegion
{
  /** Frame index in its sequence and colour timestamp (s). */
  uint64_t frame = 0;
  double timestamp = 0;
  /** The region's box in the frame, and the frame's size (pixels). */
  cv::Rect box;
  cv::Size imageSize;
  /** Intrinsics of the frame (for the observation's field of view). */
  mrpt::img::TCamera camera;
  /** The region's features (keypoints in frame pixels). */
  features::TFeatureSet features;
  /** Optical-frame 3-D point of each feature (parallel to features, NaN = no
   *  depth); empty: no 3-D check of a recall, no landmark position. */
  std::vector<mrpt::math::TPoint3D> points;
  /** The region's position (component-wise median of its points), optical
   *  frame, metres. */
  std::optional<mrpt::math::TPoint3D> position;
  /** The same in the world, when the camera pose is known: new landmarks
   *  store it and the database prefilters by it. */
  std::optional<mrpt::math::TPoint3D> worldPosition;
  /** Image patch stored with a new landmark (may be empty). */
  cv::Mat patch;
  /** Optional, both or neither: the whole frame's features and its depth
   *  (CV_32FC1 metres). A recall without a 3-D fit is then located by the
   *  depth of the frame's features inside the recalled landmark's box. */
  const features::TFeatureSet* frameFeatures = nullptr;
  const cv::Mat* depth = nullptr;
};
}  // namespace roislam::landmarks
