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

cv::Rect regionOfArea(const cv::Rect& region, const cv::Size& image, double area, double minAspect)
{
  double w = std::max(region.width, 1), h = std::max(region.height, 1);
  w = std::max(w, minAspect * h);
  h = std::max(h, minAspect * w);
  const double s = std::sqrt(area * image.area() / (w * h));
  // Clamped to the image: a region wider than the image gives its excess
  // area to the height (and the other way round).
  w = std::min<double>(image.width, w * s);
  h = std::min<double>(image.height, std::max(h * s, area * image.area() / w));
  w = std::min<double>(image.width, std::max(w, area * image.area() / h));
  const int W = std::max(1, static_cast<int>(std::lround(w)));
  const int H = std::max(1, static_cast<int>(std::lround(h)));
  const double cx = region.x + 0.5 * region.width, cy = region.y + 0.5 * region.height;
  const int x = std::clamp(static_cast<int>(std::lround(cx - 0.5 * W)), 0, image.width - W);
  const int y = std::clamp(static_cast<int>(std::lround(cy - 0.5 * H)), 0, image.height - H);
  return cv::Rect(x, y, W, H);
}

/** The reference keyframe's tracking region as this frame should see it:
 *  its centre, at the region's median depth, moved by the predicted motion
 *  (keyframe -> frame) and projected; its size scaled by the change of
 *  depth. Not the bounding box of its moved corners: under a roll that box
 *  is up to 1.4 times wider and higher, and since each keyframe stores the
 *  region it followed, the region would ratchet up keyframe by keyframe
 *  towards the whole image. Empty when it leaves the image. */
cv::Rect followRegion(
    const TKeyframe& kf, const mrpt::poses::CPose3D& predictedRel, const detail::TPinhole& cam,
    const cv::Size& image)
{
  if (kf.region.empty() || !(kf.regionDepth > 0))
    return {};
  const double z = kf.regionDepth;
  const double u = kf.region.x + 0.5 * kf.region.width, v = kf.region.y + 0.5 * kf.region.height;
  double X, Y, Z;
  (-predictedRel).composePoint((u - cam.cx) / cam.fx * z, (v - cam.cy) / cam.fy * z, z, X, Y, Z);
  if (!(Z > 0.05))
    return {};
  const double scale = z / Z;
  const double w = kf.region.width * scale, h = kf.region.height * scale;
  const double cu = cam.fx * X / Z + cam.cx, cv = cam.fy * Y / Z + cam.cy;
  const cv::Rect predicted(
      static_cast<int>(std::lround(cu - 0.5 * w)), static_cast<int>(std::lround(cv - 0.5 * h)),
      static_cast<int>(std::lround(w)), static_cast<int>(std::lround(h)));
  const cv::Rect inside = predicted & cv::Rect(0, 0, image.width, image.height);
  // Mostly out of view: the region is lost, stage 1 finds a new one.
  if (inside.area() < 0.5 * predicted.area())
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
