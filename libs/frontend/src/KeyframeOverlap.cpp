#include "KeyframeOverlap.h"

#include <algorithm>
#include <utility>

namespace roislam::frontend::detail
{
double viewOverlap(
    const TKeyframe& kf, const mrpt::poses::CPose3D& rel, const TViewModel& view,
    std::size_t samples)
{
  const std::size_t n = kf.points.size();
  if (n == 0)
    return 0;
  const std::size_t step = samples > 0 && n > samples ? n / samples : 1;
  std::size_t tested = 0, seen = 0;
  for (std::size_t i = 0; i < n; i += step)
  {
    ++tested;
    double x, y, z;
    rel.inverseComposePoint(kf.points[i].x, kf.points[i].y, kf.points[i].z, x, y, z);
    if (!(z >= view.minDepth && z <= view.maxDepth && z > 0))
      continue;
    const cv::Point2f u = view.camera.project({x, y, z});
    if (u.x >= 0 && u.y >= 0 && u.x < view.image.width && u.y < view.image.height)
      ++seen;
  }
  return static_cast<double>(seen) / static_cast<double>(tested);
}

std::vector<std::size_t> bestOverlapping(
    const std::deque<TKeyframe>& keyframes, const mrpt::poses::CPose3D& predicted,
    const TViewModel& view, std::size_t n, std::size_t samples)
{
  std::vector<std::pair<double, std::size_t>> scored;
  for (const TKeyframe& kf : keyframes)
  {
    const double ov = viewOverlap(kf, predicted - kf.pose, view, samples);
    if (ov > 0)
      scored.emplace_back(ov, kf.id);
  }
  // Best overlap first; among equals the newer keyframe (less drift to it).
  std::sort(
      scored.begin(), scored.end(),
      [](const auto& a, const auto& b)
      { return a.first != b.first ? a.first > b.first : a.second > b.second; });
  std::vector<std::size_t> ids;
  for (std::size_t i = 0; i < scored.size() && i < n; ++i)
    ids.push_back(scored[i].second);
  return ids;
}
}  // namespace roislam::frontend::detail
