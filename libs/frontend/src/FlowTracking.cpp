#include "FlowTracking.h"

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

namespace roislam::frontend::detail
{
int flowShift(const cv::Size& image)
{
  int shift = 0;
  while ((image.width >> (shift + 1)) >= 640)
    ++shift;
  return shift;
}

cv::Point2f toFlowLevel(const cv::Point2f& u, int shift)
{
  if (shift == 0)
    return u;
  const float s = static_cast<float>(1 << shift);
  const float o = 0.5f * (s - 1.0f);
  return {(u.x - o) / s, (u.y - o) / s};
}

cv::Point2f fromFlowLevel(const cv::Point2f& u, int shift)
{
  const float s = static_cast<float>(1 << shift);
  const float o = 0.5f * (s - 1.0f);
  return {s * u.x + o, s * u.y + o};
}

TFlowPyramid flowPyramid(const cv::Mat& grey, const TFlowParams& p, bool withDerivatives)
{
  cv::Mat tracked = grey;
  for (int i = flowShift(grey.size()); i > 0; --i)
    cv::pyrDown(tracked, tracked);
  return flowPyramidOfTracked(tracked, p, withDerivatives);
}

TFlowPyramid flowPyramidOfTracked(
    const cv::Mat& tracked, const TFlowParams& p, bool withDerivatives)
{
  TFlowPyramid pyr;
  cv::buildOpticalFlowPyramid(
      tracked, pyr, cv::Size(p.window, p.window), p.levels, withDerivatives);
  return pyr;
}

features::TFeatureSet anchorCandidates(const cv::Mat& grey, const TFlowParams& p)
{
  // Found at half resolution: Shi-Tomasi's eigenvalue image over the whole
  // frame was most of a keyframe's flow work (640 x 480: 4.2-4.9 ms, at half
  // resolution 0.55-0.8 ms). Where exactly in its corner an anchor sits
  // matters little: Lucas-Kanade follows its window's texture from wherever
  // the keyframe puts it.
  const int shift = flowShift(grey.size()) + 1;
  const double f = 1.0 / static_cast<double>(1 << shift);
  cv::Mat half;
  cv::resize(grey, half, cv::Size(), f, f, cv::INTER_AREA);
  std::vector<cv::Point2f> corners;
  // A window apart (at the tracked resolution): no two anchors share their
  // window, the spacing bounds their number (about 700 on 640 x 480) and
  // the quality keeps them to the textured parts. Measured on the fr1
  // excerpts (12 mode x extractor runs, full resolution): half a window
  // apart followed about 300 anchors a frame for the same accuracy as about
  // 120 a window apart (mean ATE / traditional 1.07 both).
  const double minDistance = 0.5 * p.window;
  cv::goodFeaturesToTrack(half, corners, 0, p.anchorQuality, minDistance);
  features::TFeatureSet s;
  s.keypoints.reserve(corners.size());
  // Pixel centres: inside the image for every u of the reduced one.
  for (const auto& c : corners)
    s.keypoints.emplace_back(fromFlowLevel(c, shift), 0.0f);
  return s;
}

std::vector<int> spacedStrongest(
    const std::vector<cv::KeyPoint>& keypoints, const cv::Size& image, const TFlowParams& p)
{
  const float minDist = static_cast<float>(p.window * (1 << flowShift(image)));
  std::vector<int> order(keypoints.size());
  for (std::size_t i = 0; i < order.size(); ++i)
    order[i] = static_cast<int>(i);
  // Ties keep the set's order (deterministic).
  std::stable_sort(
      order.begin(), order.end(),
      [&](int a, int b)
      {
        return keypoints[static_cast<std::size_t>(a)].response >
               keypoints[static_cast<std::size_t>(b)].response;
      });
  // A grid of minDist cells: a taken keypoint's neighbours within minDist
  // are in its cell or the eight around it.
  const int cols = std::max(1, static_cast<int>(std::ceil(image.width / minDist)));
  const int rows = std::max(1, static_cast<int>(std::ceil(image.height / minDist)));
  std::vector<std::vector<cv::Point2f>> cells(static_cast<std::size_t>(cols * rows));
  const auto cellOf = [&](float v, int n)
  { return std::clamp(static_cast<int>(v / minDist), 0, n - 1); };
  std::vector<int> taken;
  for (int i : order)
  {
    const cv::Point2f u = keypoints[static_cast<std::size_t>(i)].pt;
    const int cx = cellOf(u.x, cols), cy = cellOf(u.y, rows);
    bool free = true;
    for (int y = std::max(0, cy - 1); free && y <= std::min(rows - 1, cy + 1); ++y)
      for (int x = std::max(0, cx - 1); free && x <= std::min(cols - 1, cx + 1); ++x)
        for (const auto& q : cells[static_cast<std::size_t>(y * cols + x)])
          if ((q.x - u.x) * (q.x - u.x) + (q.y - u.y) * (q.y - u.y) < minDist * minDist)
          {
            free = false;
            break;
          }
    if (!free)
      continue;
    cells[static_cast<std::size_t>(cy * cols + cx)].push_back(u);
    taken.push_back(i);
  }
  return taken;
}

TFlowTracks followAnchors(
    const TKeyframe& kf, const TFlowPyramid& kfPyramid, const TFlowPyramid& curPyramid,
    const mrpt::poses::CPose3D& predictedRel, const cv::Mat& K, const cv::Mat& dist,
    const cv::Size& image, const cv::Rect& described, const TFlowParams& p)
{
  TFlowTracks out;
  out.set.type = kf.features.type;
  if (kf.anchorPoints.empty() || kfPyramid.empty() || curPyramid.empty())
    return out;
  // Where the predicted motion puts each anchor in this frame.
  std::vector<cv::Point3f> inCurrent;
  std::vector<int> idx;
  inCurrent.reserve(kf.anchorPoints.size());
  for (std::size_t i = 0; i < kf.anchorPoints.size(); ++i)
  {
    const auto& a = kf.anchorPoints[i];
    double x, y, z;
    predictedRel.inverseComposePoint(a.x, a.y, a.z, x, y, z);
    if (z > 0.05)
    {
      inCurrent.emplace_back(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z));
      idx.push_back(static_cast<int>(i));
    }
  }
  if (inCurrent.empty())
    return out;
  std::vector<cv::Point2f> predicted;
  cv::projectPoints(inCurrent, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, dist, predicted);
  const int shift = flowShift(image);
  const cv::Rect2f inside(2.0f, 2.0f, image.width - 4.0f, image.height - 4.0f);
  const cv::Rect2f describedBox(described);
  std::vector<cv::Point2f> from, to;
  std::vector<int> which;
  for (std::size_t j = 0; j < predicted.size(); ++j)
  {
    // Where the frame's own features were described, they carry the pose:
    // following there too would only repeat it (a big ROI is most of the
    // image, and its flow then cost as much as its description).
    if (!inside.contains(predicted[j]) || describedBox.contains(predicted[j]))
      continue;
    from.push_back(toFlowLevel(kf.anchorKeypoints[static_cast<std::size_t>(idx[j])], shift));
    to.push_back(toFlowLevel(predicted[j], shift));
    which.push_back(idx[j]);
  }
  if (from.empty())
    return out;
  std::vector<uchar> status;
  std::vector<float> err;
  cv::calcOpticalFlowPyrLK(
      kfPyramid, curPyramid, from, to, status, err, cv::Size(p.window, p.window), p.levels,
      cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 30, 0.01),
      cv::OPTFLOW_USE_INITIAL_FLOW);
  for (std::size_t j = 0; j < from.size(); ++j)
  {
    const cv::Point2f at = fromFlowLevel(to[j], shift);
    if (!status[j] || !inside.contains(at))
      continue;
    out.set.keypoints.emplace_back(at, 0.0f);
    out.anchorIndex.push_back(which[j]);
  }
  // Zero descriptors of the features' layout keep the set a valid one; the
  // followed anchors are never matched.
  const cv::Mat& d = kf.features.descriptors;
  if (!out.set.keypoints.empty() && !d.empty())
    out.set.descriptors =
        cv::Mat::zeros(static_cast<int>(out.set.keypoints.size()), d.cols, d.type());
  return out;
}

TKeyframe withAnchors(const TKeyframe& kf)
{
  TKeyframe v;
  v.id = kf.id;
  v.frameIndex = kf.frameIndex;
  v.timestamp = kf.timestamp;
  v.pose = kf.pose;
  v.features = kf.features;
  v.index = kf.index;
  v.points = kf.points;
  v.pixels = kf.pixels;
  v.angularRate = kf.angularRate;
  v.linearRate = kf.linearRate;
  v.points.insert(v.points.end(), kf.anchorPoints.begin(), kf.anchorPoints.end());
  v.pixels.insert(v.pixels.end(), kf.anchorPixels.begin(), kf.anchorPixels.end());
  return v;
}
}  // namespace roislam::frontend::detail
