#include "roislam/testing/TestData.h"

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
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
  // 7-Scenes' own layout (rgbd-simul layout = 7scenes).
  if (fs::exists(p / "frame-000000.color.png") && fs::exists(p / "frame-000000.pose.txt"))
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

CTempDir::CTempDir(const std::string& prefix) : m_path(makeTempDir(prefix)) {}

CTempDir::~CTempDir()
{
  std::error_code ec;
  fs::remove_all(m_path, ec);
}

TAppRun runApp(const std::string& app, const std::string& args)
{
  const std::string exe = binaryDir() + "/apps/" + app + "/" + app;
  const std::string dir = makeTempDir("app_run");
  const int rc = std::system(
      (exe + " " + args + " > " + dir + "/stdout.txt 2> " + dir + "/stderr.txt").c_str());
  TAppRun r;
  r.exitCode = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  const auto read = [](const std::string& file)
  {
    std::ifstream f(file);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
  };
  r.out = read(dir + "/stdout.txt");
  r.err = read(dir + "/stderr.txt");
  fs::remove_all(dir);
  return r;
}
}  // namespace roislam::testing
