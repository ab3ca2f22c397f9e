#include "TrackingRegion.h"

#include <algorithm>
#include <cmath>

namespace roislam::frontend::detail
{
/** The ROI grown about its centre to a minimum share of the image and a
 *  minimum aspect (short side / long side), moved inside the image. */
cv::Rect trackingRegion(
    const cv::Rect& roi, const cv::Size& image, double minArea, double minAspect)
{
  double w = std::max(roi.width, 1), h = std::max(roi.height, 1);
  w = std::max(w, minAspect * h);
  h = std::max(h, minAspect * w);
  const double area = minArea * image.area();
  if (w * h < area)
  {
    const double s = std::sqrt(area / (w * h));
    w *= s;
    h *= s;
  }
  const int W = std::min(image.width, static_cast<int>(std::ceil(w)));
  const int H = std::min(image.height, static_cast<int>(std::ceil(h)));
  const double cx = roi.x + 0.5 * roi.width, cy = roi.y + 0.5 * roi.height;
  const int x = std::clamp(static_cast<int>(std::lround(cx - 0.5 * W)), 0, image.width - W);
  const int y = std::clamp(static_cast<int>(std::lround(cy - 0.5 * H)), 0, image.height - H);
  return cv::Rect(x, y, W, H) | roi;  // never smaller than the ROI itself
}

/** The reference keyframe's tracking region as this frame should see it:
 *  its corners, at the region's median depth, moved by the predicted motion
 *  (keyframe -> frame) and projected. Empty when it leaves the image. */
cv::Rect followRegion(
    const TKeyframe& kf, const mrpt::poses::CPose3D& predictedRel, const detail::TPinhole& cam,
    const cv::Size& image)
{
  if (kf.region.empty() || !(kf.regionDepth > 0))
    return {};
  const mrpt::poses::CPose3D toFrame = -predictedRel;
  float x0 = 1e9F, y0 = 1e9F, x1 = -1e9F, y1 = -1e9F;
  for (int c = 0; c < 4; ++c)
  {
    const double u = kf.region.x + (c & 1 ? kf.region.width : 0);
    const double v = kf.region.y + (c & 2 ? kf.region.height : 0);
    const double z = kf.regionDepth;
    double X, Y, Z;
    toFrame.composePoint((u - cam.cx) / cam.fx * z, (v - cam.cy) / cam.fy * z, z, X, Y, Z);
    if (!(Z > 0.05))
      return {};
    const auto pu = static_cast<float>(cam.fx * X / Z + cam.cx);
    const auto pv = static_cast<float>(cam.fy * Y / Z + cam.cy);
    x0 = std::min(x0, pu);
    y0 = std::min(y0, pv);
    x1 = std::max(x1, pu);
    y1 = std::max(y1, pv);
  }
  const cv::Rect predicted(
      cv::Point(static_cast<int>(std::floor(x0)), static_cast<int>(std::floor(y0))),
      cv::Point(static_cast<int>(std::ceil(x1)), static_cast<int>(std::ceil(y1))));
  const cv::Rect inside = predicted & cv::Rect(0, 0, image.width, image.height);
  // Mostly out of view: the region is lost, stage 1 finds a new one.
  if (inside.area() < 0.5 * predicted.area() || inside.area() < 0.5 * kf.region.area())
    return {};
  return inside;
}

/** The image outside `region`, as up to four bands (above, below, left,
 *  right), which together cover every pixel once. */
std::vector<cv::Rect> outside(const cv::Rect& region, const cv::Size& image)
{
  const cv::Rect r = region & cv::Rect(0, 0, image.width, image.height);
  std::vector<cv::Rect> bands = {
      cv::Rect(0, 0, image.width, r.y),
      cv::Rect(0, r.y + r.height, image.width, image.height - r.y - r.height),
      cv::Rect(0, r.y, r.x, r.height),
      cv::Rect(r.x + r.width, r.y, image.width - r.x - r.width, r.height)};
  bands.erase(
      std::remove_if(bands.begin(), bands.end(), [](const cv::Rect& b) { return b.empty(); }),
      bands.end());
  return bands;
}
}  // namespace roislam::frontend::detail
