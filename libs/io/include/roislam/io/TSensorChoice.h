/* A resolved --camera value: the sensor description a frame source uses, where
 * it came from and why it was picked. Produced by resolveSensor() and the
 * frame sources (CFrameSource::sensor()); the apps print summary() and record
 * toJson() in summary.json, so that no choice of camera is silent.
 */
#pragma once

#include <roislam/io/TSensorDescription.h>

#include <nlohmann/json.hpp>
#include <string>

namespace roislam::io
{
struct TSensorChoice
{
  TSensorDescription sensor;
  /** "preset fr1", "file /path/camera.ini", "rawlog observations", "OpenNI2 device". */
  std::string source;
  /** Why this description was picked ("--camera fr1", "camera.ini in the folder", ...). */
  std::string reason;

  /** One line: name, source, reason, intrinsics, registration, readout, rate, noise. */
  std::string summary() const;
  /** {name, source, reason, description (the ini text)} for summary.json. */
  nlohmann::json toJson() const;
};
}  // namespace roislam::io
