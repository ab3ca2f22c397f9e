#include <roislam/viz/SceneBounds.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace roislam::viz
{
std::optional<mrpt::math::TBoundingBox> robustBounds(const TSceneContent& content, double fraction)
{
  std::array<double, 3> lo = {1e30, 1e30, 1e30}, hi = {-1e30, -1e30, -1e30};
  auto grow = [&](const mrpt::math::TPoint3D& p)
  {
    for (int k = 0; k < 3; ++k)
    {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  };
  const std::size_t n = content.cloud.size();
  if (n > 0)
  {
    // At most ~20000 points: quantiles need no more.
    const std::size_t step = std::max<std::size_t>(1, n / 20000);
    std::array<std::vector<double>, 3> axes;
    for (std::size_t i = 0; i < n; i += step)
    {
      float x, y, z;
      content.cloud.getPoint(i, x, y, z);
      axes[0].push_back(x);
      axes[1].push_back(y);
      axes[2].push_back(z);
    }
    for (int k = 0; k < 3; ++k)
    {
      auto& v = axes[k];
      const auto at = [&](double q)
      {
        const auto idx = static_cast<std::size_t>(std::lround(q * (v.size() - 1)));
        std::nth_element(v.begin(), v.begin() + idx, v.end());
        return v[idx];
      };
      lo[k] = std::min(lo[k], at(fraction));
      hi[k] = std::max(hi[k], at(1.0 - fraction));
    }
  }
  for (const auto* list : {&content.trajectory, &content.groundTruth, &content.keyframes})
    for (const auto& p : *list)
      grow(p);
  if (lo[0] > hi[0])
    return std::nullopt;
  return mrpt::math::TBoundingBox({lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]});
}

double niceGridSpacing(double extent)
{
  if (!(extent > 0))
    return 1.0;
  // The largest 1-2-5 step with at least 4 cells.
  const double raw = extent / 4;
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {5.0, 2.0, 1.0})
    if (m * decade <= raw)
      return m * decade;
  return decade;
}
}  // namespace roislam::viz
