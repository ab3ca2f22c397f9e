#include "KeyframeOverlap.h"

#include <algorithm>
#include <utility>

#include "RigidMath.h"

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

std::vector<std::size_t> referenceCandidates(
    const std::deque<TKeyframe>& keyframes, const mrpt::poses::CPose3D& predicted,
    const TViewModel& view, const TReferenceGate& gate, std::size_t n, std::size_t samples)
{
  std::vector<std::size_t> ids;
  std::vector<std::pair<double, std::size_t>> others;
  for (std::size_t k = keyframes.size(); k-- > 0;)
  {
    const TKeyframe& kf = keyframes[k];
    const mrpt::poses::CPose3D rel = predicted - kf.pose;
    const double ov = viewOverlap(kf, rel, view, samples);
    const bool near = (!(gate.maxDistance > 0) || rel.translation().norm() <= gate.maxDistance) &&
                      (!(gate.maxAngleRad > 0) || rotationAngle(rel) <= gate.maxAngleRad);
    if (ov >= gate.minOverlap && ov > 0 && near)
    {
      if (ids.size() < n)
        ids.push_back(kf.id);
    }
    else if (ov > 0)
      others.emplace_back(ov, kf.id);
  }
  // Stable: among equal overlaps the newer keyframe stays first.
  std::stable_sort(
      others.begin(), others.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  for (std::size_t i = 0; i < others.size() && ids.size() < n; ++i)
    ids.push_back(others[i].second);
  return ids;
}

std::vector<std::size_t> keyframesNear(
    const std::deque<TKeyframe>& keyframes, const mrpt::poses::CPose3D& pose, double maxDistance,
    double maxAngleRad)
{
  std::vector<std::pair<double, std::size_t>> near;
  for (const TKeyframe& kf : keyframes)
  {
    const mrpt::poses::CPose3D rel = pose - kf.pose;
    const double d = rel.translation().norm() / maxDistance;
    const double a = rotationAngle(rel) / maxAngleRad;
    if (d <= 1 && a <= 1)
      near.emplace_back(std::max(d, a), kf.id);
  }
  std::stable_sort(
      near.begin(), near.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<std::size_t> ids;
  for (const auto& n : near)
    ids.push_back(n.second);
  return ids;
}
}  // namespace roislam::frontend::detail
