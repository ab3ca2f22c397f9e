#include "roislam/gui/FrameOverlay.h"

#include <opencv2/imgproc.hpp>
#include <string>

namespace roislam::gui
{
namespace
{
bool isFallback(frontend::ETrackingMethod m)
{
  using M = frontend::ETrackingMethod;
  return m == M::FullImageFallback || m == M::DepthIcp || m == M::ConstantVelocity || m == M::Lost;
}

void drawCaption(cv::Mat& img, const TLiveFrame& f)
{
  const std::string line1 = frontend::toString(f.method) + (f.isNewKeyframe ? "  (keyframe)" : "");
  const std::string line2 = std::to_string(f.trackingFeatures) + " tracked / " +
                            std::to_string(f.features) + " features, " + std::to_string(f.inliers) +
                            " inliers";
  const double scale = img.cols / 640.0;
  const int h = static_cast<int>(22 * scale);
  cv::rectangle(img, cv::Rect(0, 0, img.cols, 2 * h + 6), cv::Scalar(0, 0, 0), cv::FILLED);
  const cv::Scalar c1 =
      isFallback(f.method) ? TOverlayColours::fallback() : cv::Scalar(255, 255, 255);
  cv::putText(
      img, line1, {6, h}, cv::FONT_HERSHEY_SIMPLEX, 0.6 * scale, c1, std::max(1, int(2 * scale)),
      cv::LINE_AA);
  cv::putText(
      img, line2, {6, 2 * h}, cv::FONT_HERSHEY_SIMPLEX, 0.5 * scale, cv::Scalar(220, 220, 220), 1,
      cv::LINE_AA);
}
}  // namespace

bool isTrackedFeature(const TLiveFrame& frame, const cv::Point2f& pixel, bool roiMode)
{
  if (!roiMode)
    return true;
  if (!frame.region.empty())
    return frame.region.contains(pixel);
  return frame.roi && frame.roi->contains(pixel);
}

cv::Mat drawFrameOverlay(const TLiveFrame& frame, bool roiMode)
{
  if (frame.rgb.empty())
    return {};
  cv::Mat img = frame.rgb.clone();
  const int thick = std::max(1, img.cols / 320);
  for (const auto& p : frame.featurePixels)
    cv::circle(
        img, p, 2 * thick,
        isTrackedFeature(frame, p, roiMode) ? TOverlayColours::tracked()
                                            : TOverlayColours::extension(),
        thick, cv::LINE_AA);
  if (!frame.region.empty() && (!frame.roi || *frame.roi != frame.region))
    cv::rectangle(img, frame.region, TOverlayColours::region(), thick);
  if (frame.roi)
    cv::rectangle(img, *frame.roi, TOverlayColours::roiBox(), 2 * thick);
  drawCaption(img, frame);
  return img;
}

cv::Mat colouriseDepth(const cv::Mat& depth, double maxDepthM)
{
  if (depth.empty())
    return {};
  cv::Mat grey;
  depth.convertTo(grey, CV_8U, 255.0 / maxDepthM);
  cv::Mat colour;
  cv::applyColorMap(grey, colour, cv::COLORMAP_TURBO);
  colour.setTo(cv::Scalar(0, 0, 0), depth <= 0);
  return colour;
}
}  // namespace roislam::gui
