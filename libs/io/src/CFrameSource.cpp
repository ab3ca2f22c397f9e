#include "roislam/io/CFrameSource.h"

#include <roislam/io/COpenNI2FrameSource.h>
#include <roislam/io/CRawlogFrameSource.h>
#include <roislam/io/CTumFrameSource.h>
#include <roislam/io/CameraPresets.h>

#include <filesystem>
#include <stdexcept>

namespace fs = std::filesystem;

namespace roislam::io
{
double CFrameSource::colourTime(double stamp)
{
  const TSensorDescription& d = m_sensor.sensor;
  double t = stamp;
  if (d.regular_frame_clock)
  {
    if (!m_clock)
      m_clock.emplace(d.frame_rate);
    t = m_clock->time(stamp);
  }
  return t + d.colour_time_offset_ms * 1e-3;
}

std::optional<TFrameClockStats> CFrameSource::frameClock() const
{
  if (!m_sensor.sensor.regular_frame_clock)
    return std::nullopt;
  return m_clock ? m_clock->stats() : TFrameClockStats{};
}

void CFrameSource::seek(std::size_t index)
{
  if (index >= size())
    throw std::out_of_range(name() + ": no frame " + std::to_string(index));
  rewind();
  for (std::size_t i = 0; i < index; ++i)
    next();
}

std::unique_ptr<CFrameSource> CFrameSource::open(
    const std::string& path, const std::string& cameraSpec)
{
  if (COpenNI2FrameSource::isDeviceSpec(path))
  {
    // A live device has no folder: "auto" lets the device describe itself.
    std::optional<TSensorChoice> given;
    if (cameraSpec != "auto")
      given = resolveSensor(cameraSpec, ".");
    return std::make_unique<COpenNI2FrameSource>(path, given);
  }
  if (fs::is_directory(path))
    return std::make_unique<CTumFrameSource>(
        path, resolveSensor(cameraSpec, path), CTumFrameSource::TOptions());
  if (!fs::exists(path))
    throw std::runtime_error(path + ": no such file or folder");
  if (fs::path(path).extension() == ".oni")
    return std::make_unique<COpenNI2FrameSource>(path, resolveSensorForFile(cameraSpec, path));
  // A rawlog's observations carry their own depth geometry and units; a
  // description replaces the colour intrinsics and brings the camera facts.
  const auto choice = resolveSensorForFile(cameraSpec, path);
  std::optional<mrpt::img::TCamera> override;
  if (choice)
    override = choice->sensor.colour;
  auto source =
      std::make_unique<CRawlogFrameSource>(path, CRawlogFrameSource::TOptions(), override);
  if (choice)
    static_cast<CFrameSource&>(*source).m_sensor = *choice;
  return source;
}
}  // namespace roislam::io
