#include <mrpt/core/format.h>
#include <roislam/frontend/SensorNoise.h>
#include <roislam/graphslam/SensorFacts.h>
#include <roislam/graphslam/SlamIni.h>

namespace roislam::graphslam
{
bool iniSetsReadout(const mrpt::config::CConfigFileBase& cfg, const std::string& fileLabel)
{
  const std::string section = slamIniLayout(cfg, fileLabel) == ESlamIniLayout::RoiGraphSlam
                                  ? "FrontEnd"
                                  : "NodeRegistrationDeciderParameters";
  return cfg.keyExists(section, "rolling_shutter_ms");
}

void applySensorFacts(
    frontend::CRgbdOdometry::TOptions& fe, const io::TSensorChoice& choice, bool iniReadout,
    const std::string& app, const std::string& iniFile,
    const std::function<void(const std::string&)>& progress)
{
  if (progress)
    progress(app + ": " + choice.summary());
  frontend::applySensorNoise(fe, choice.sensor);
  const double sensorMs = choice.sensor.frameReadoutMs();
  if (!iniReadout)
    fe.rolling_shutter_ms = sensorMs;
  else if (fe.rolling_shutter_ms != sensorMs && progress)
    progress(mrpt::format(
        "%s: note: %s sets rolling_shutter_ms = %g, which overrides the sensor's %g ms (the "
        "readout is a camera fact: it moved to the sensor description)",
        app.c_str(), iniFile.c_str(), fe.rolling_shutter_ms, sensorMs));
}

std::string readoutOrigin(bool iniReadout)
{
  return iniReadout ? "ini" : "sensor description";
}
}  // namespace roislam::graphslam
