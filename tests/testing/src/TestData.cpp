#include "roislam/testing/TestData.h"

#include <cstdlib>
#include <filesystem>
#include <stdexcept>

namespace fs = std::filesystem;

namespace roislam::testing
{
std::string sharedDataDir()
{
  return ROISLAM_SHARED_DATA_DIR;
}

std::optional<std::string> sharedTumSequence()
{
  const fs::path p =
      fs::path(ROISLAM_SHARED_DATA_DIR) / "tum" / "rgbd_dataset_freiburg1_rpy_first250";
  if (fs::exists(p / "rgb.txt") && fs::exists(p / "depth.txt"))
    return p.string();
  return std::nullopt;
}

std::optional<std::string> syntheticSequence(const std::string& scene)
{
  const fs::path p = fs::path(ROISLAM_SYNTH_DATA_DIR) / scene;
  if (fs::exists(p / "rgb.txt") && fs::exists(p / "groundtruth.txt"))
    return p.string();
  return std::nullopt;
}

std::string sourceDir()
{
  return ROISLAM_SOURCE_DIR;
}
std::string binaryDir()
{
  return ROISLAM_BINARY_DIR;
}

std::string makeTempDir(const std::string& prefix)
{
  std::string tmpl = (fs::temp_directory_path() / (prefix + "_XXXXXX")).string();
  if (!mkdtemp(tmpl.data()))
    throw std::runtime_error("cannot create temporary folder " + tmpl);
  return tmpl;
}
}  // namespace roislam::testing
