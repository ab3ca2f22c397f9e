/* The median the libraries' robust estimators share (the front end's depth
 * time offset, ICP consistency and tracking-region depth, the graph's
 * variance factor, the feature bench's keypoint noise, the stamps' period):
 * the upper one of an even count, no averaging, so that it is always one of
 * the samples. */
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace roislam::common
{
/** The element at size / 2 in sorted order; v must not be empty. */
inline double upperMedian(std::vector<double> v)
{
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}
}  // namespace roislam::common
