/* What the live view keeps of one SLAM frame: copied on the SLAM thread
 * (makeLiveFrame(), a few microseconds: no image is copied unless asked
 * for) and handed to the drawing thread, which owns it from then on. Made
 * by CLiveView::onFrame, drawn by CLiveScene (poses, keyframe cloud, loop
 * closures) and drawFrameOverlay() (image, ROI, features).
 */
#pragma once

#include <mrpt/math/TPoint3D.h>
#include <mrpt/poses/CPose3D.h>
#include <roislam/frontend/TFrameResult.h>
#include <roislam/graphslam/CSlamContext.h>
#include <roislam/io/TRGBDFrame.h>

#include <cstddef>
#include <opencv2/core.hpp>
#include <optional>
#include <utility>
#include <vector>

namespace roislam::gui
{
/** A keyframe's map cloud, decimated, in its camera's optical frame. */
using TKeyframeCloud = std::vector<mrpt::math::TPointXYZfRGBAu8>;

struct TLiveFrame
{
  std::size_t index = 0;
  double timestamp = 0;
  /** When the SLAM thread finished it (s, the view's clock). */
  double processedAt = 0;
  frontend::ETrackingMethod method = frontend::ETrackingMethod::Lost;
  /** The front end's world pose (nullopt when Lost). */
  std::optional<mrpt::poses::CPose3D> pose;
  std::size_t referenceKeyframe = 0;
  /** pose = keyframe(referenceKeyframe) (+) relativePose. */
  mrpt::poses::CPose3D relativePose;
  bool isNewKeyframe = false;
  std::size_t newKeyframeId = 0;
  /** New keyframes only. */
  std::optional<TKeyframeCloud> cloud;

  std::optional<cv::Rect> roi;
  /** The tracking region (roi_extraction = region), else empty. */
  cv::Rect region;
  std::size_t features = 0, trackingFeatures = 0, inliers = 0;
  frontend::EExtension extension = frontend::EExtension::None;

  /** Only when the image was taken (makeLiveFrame's withImage): colour
   *  (BGR), depth (m) and the pixels of the features described. */
  cv::Mat rgb, depth;
  std::vector<cv::Point2f> featurePixels;

  /** Totals after this frame. */
  std::size_t keyframes = 0, loopClosures = 0, fallbackFrames = 0, lostFrames = 0;
  /** Every accepted closure still in the graph (from, to keyframe), when
   *  the list changed with this frame; nullopt when it did not. */
  std::optional<std::vector<std::pair<std::size_t, std::size_t>>> loops;
};

/** The accepted loop closures of `context` as (from, to) keyframe pairs. */
std::vector<std::pair<std::size_t, std::size_t>> loopPairs(const graphslam::CSlamContext& context);

/** Copies what the view needs of a frame. The images are shared when
 *  OpenCV owns them (reference-counted, never written again by the
 *  pipeline) and copied otherwise; a new keyframe's cloud is cut to at most
 *  `maxCloudPoints` points (evenly). `loopsSeen`: the closure count the
 *  view knows; the list is copied when it differs. */
TLiveFrame makeLiveFrame(
    const frontend::TFrameResult& result, const io::TRGBDFrame& frame,
    const graphslam::CSlamContext& context, bool withImage, std::size_t maxCloudPoints,
    std::size_t loopsSeen);
}  // namespace roislam::gui
