#include "roislam/io/CameraPresets.h"

#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/containers/yaml.h>
#include <mrpt/io/vector_loadsave.h>
#include <roislam/common/CStrictIniFile.h>
#include <roislam/common/StrictYaml.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "MrptErrorText.h"

namespace fs = std::filesystem;

namespace roislam::io
{
namespace
{
mrpt::img::TCamera makeCamera(
    const std::string& name, double fx, double fy, double cx, double cy,
    const std::array<double, 5>& dist)
{
  mrpt::img::TCamera cam;
  cam.ncols = 640;
  cam.nrows = 480;
  cam.setIntrinsicParamsFromValues(fx, fy, cx, cy);
  cam.dist.fill(0);
  bool anyDistortion = false;
  for (std::size_t i = 0; i < dist.size(); ++i)
  {
    cam.dist[i] = dist[i];
    anyDistortion = anyDistortion || dist[i] != 0;
  }
  cam.distortion =
      anyDistortion ? mrpt::img::DistortionModel::plumb_bob : mrpt::img::DistortionModel::none;
  cam.cameraName = name;
  return cam;
}

bool validCamera(const mrpt::img::TCamera& c)
{
  return c.ncols > 0 && c.nrows > 0 && c.fx() > 0 && c.fy() > 0;
}

mrpt::img::TCamera loadIniCamera(const std::string& file)
{
  if (!fs::is_regular_file(file))
    throw std::runtime_error(file + ": camera calibration file not found");
  mrpt::img::TCamera cam;
  // Syntax first (file:line errors), then MRPT's reader on the same text.
  common::CStrictIniFile cfg(file);
  try
  {
    if (!cfg.sectionExists("CAMERA_PARAMS"))
      throw std::runtime_error("missing section [CAMERA_PARAMS]");
    // MRPT 2.x reads `dist` only with `distortion_model = plumb_bob`; files
    // in the older layout (and hand-written ones) have only `dist`, and MRPT
    // would silently load them as undistorted. Non-zero `dist` without a
    // model means plumb_bob; an explicit model is respected.
    if (cfg.read_string("CAMERA_PARAMS", "distortion_model", "").empty())
    {
      std::vector<double> dist;
      cfg.read_vector("CAMERA_PARAMS", "dist", std::vector<double>(), dist);
      if (std::any_of(dist.begin(), dist.end(), [](double d) { return d != 0; }))
        cfg.write("CAMERA_PARAMS", "distortion_model", "plumb_bob");
    }
    cam.loadFromConfigFile("CAMERA_PARAMS", cfg);
  }
  catch (const std::exception& e)
  {
    throw std::runtime_error(
        file + ": invalid camera calibration: " + detail::oneLineError(e.what()));
  }
  if (!validCamera(cam))
    throw std::runtime_error(
        file + ": invalid camera calibration: [CAMERA_PARAMS] needs positive resolution, fx, fy");
  return cam;
}

mrpt::img::TCamera loadYamlCamera(const std::string& file)
{
  mrpt::img::TCamera cam;
  const std::string text = mrpt::io::file_get_contents(file);
  common::checkStrictYaml(text, file);
  try
  {
    cam = mrpt::img::TCamera::FromYAML(mrpt::containers::yaml::FromText(text));
  }
  catch (const std::exception& e)
  {
    throw std::runtime_error(
        file + ": invalid camera calibration: " + detail::oneLineError(e.what()));
  }
  if (!validCamera(cam))
    throw std::runtime_error(
        file + ": invalid camera calibration: non-positive resolution or focal");
  return cam;
}
}  // namespace

mrpt::img::TCamera cameraPreset(const std::string& name)
{
  // TUM benchmark calibrations (colour camera), see the dataset's "file formats" page.
  if (name == "fr1")
    return makeCamera(
        "fr1", 517.306408, 516.469215, 318.643040, 255.313989,
        {0.262383, -0.953104, -0.005358, 0.002628, 1.163314});
  if (name == "fr2")
    return makeCamera(
        "fr2", 520.908620, 521.007327, 325.141442, 249.701764,
        {0.231222, -0.784899, -0.003257, -0.000105, 0.917205});
  if (name == "fr3")
    return makeCamera("fr3", 535.4, 539.2, 320.1, 247.6, {0, 0, 0, 0, 0});
  if (name == "ros")
    return makeCamera("ros", 525.0, 525.0, 319.5, 239.5, {0, 0, 0, 0, 0});
  throw std::invalid_argument("unknown camera preset '" + name + "' (expected fr1, fr2, fr3, ros)");
}

mrpt::img::TCamera resolveCamera(const std::string& spec, const std::string& datasetDir)
{
  if (spec == "fr1" || spec == "fr2" || spec == "fr3" || spec == "ros")
    return cameraPreset(spec);
  if (spec != "auto")
  {
    const std::string ext = fs::path(spec).extension().string();
    if (ext == ".yaml" || ext == ".yml")
    {
      if (!fs::is_regular_file(spec))
        throw std::runtime_error(spec + ": camera calibration file not found");
      return loadYamlCamera(spec);
    }
    return loadIniCamera(spec);
  }

  // auto: a calibration written by the simulator next to the data wins.
  const fs::path dir(datasetDir);
  if (!datasetDir.empty())
  {
    if (fs::is_regular_file(dir / "camera.ini"))
      return loadIniCamera((dir / "camera.ini").string());
    if (fs::is_regular_file(dir / "camera.yaml"))
      return loadYamlCamera((dir / "camera.yaml").string());
  }
  // Only the folder's own name counts, so a parent called "freiburg2" does not
  // decide the camera of an unrelated sequence below it.
  std::string folder = fs::absolute(dir).lexically_normal().filename().string();
  if (folder.empty())
    folder = fs::absolute(dir).lexically_normal().parent_path().filename().string();
  if (folder.find("freiburg1") != std::string::npos)
    return cameraPreset("fr1");
  if (folder.find("freiburg2") != std::string::npos)
    return cameraPreset("fr2");
  if (folder.find("freiburg3") != std::string::npos)
    return cameraPreset("fr3");
  return cameraPreset("ros");
}
}  // namespace roislam::io
