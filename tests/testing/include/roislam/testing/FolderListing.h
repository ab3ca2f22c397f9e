/* What an app left in an output folder, for the output-folder tests
 * (common::COutputFolder: complete or absent, --overwrite). */
#pragma once

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

namespace roislam::testing
{
/** Names in `dir`, sorted, without COutputFolder's manifest (.roislam-output). */
inline std::vector<std::string> outputListing(const std::filesystem::path& dir)
{
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().filename().string() != ".roislam-output")
      names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}
}  // namespace roislam::testing
