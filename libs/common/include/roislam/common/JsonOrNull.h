/* An optional figure in summary.json: its value, or null when absent
 * (no ground truth, nothing to evaluate). One spelling for every app's
 * summary, so that readers of those files see absence the same way.
 */
#pragma once

#include <nlohmann/json.hpp>
#include <optional>

namespace roislam::common
{
template <typename T>
nlohmann::json jsonOrNull(const std::optional<T>& v)
{
  return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
}
}  // namespace roislam::common
