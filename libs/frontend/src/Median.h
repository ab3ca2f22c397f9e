/* Private: the median the front end's estimators use (depth time offset,
 * ICP consistency): the upper one of an even count, no averaging. */
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace roislam::frontend::detail
{
/** The element at size / 2 in sorted order; v must not be empty. */
inline double upperMedian(std::vector<double> v)
{
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}
}  // namespace roislam::frontend::detail
