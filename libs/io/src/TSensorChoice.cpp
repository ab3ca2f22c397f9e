#include "roislam/io/TSensorChoice.h"

#include <cmath>
#include <cstdio>

namespace roislam::io
{
std::string TSensorChoice::summary() const
{
  const auto& s = sensor;
  const auto& c = s.colour;
  char intrinsics[160];
  std::snprintf(
      intrinsics, sizeof(intrinsics), "%dx%d fx %.1f fy %.1f cx %.1f cy %.1f%s",
      static_cast<int>(c.ncols), static_cast<int>(c.nrows), c.fx(), c.fy(), c.cx(), c.cy(),
      c.distortion == mrpt::img::DistortionModel::none ? ", no distortion" : ", distorted");
  char rest[320];
  std::snprintf(
      rest, sizeof(rest),
      ", rolling shutter %g ms%s, %g Hz, depth scale %g, depth noise %s, common keypoint shift "
      "%g px, keypoint noise %g px + image speed x %g ms",
      s.rolling_shutter_ms,
      s.rolling_shutter_ms == 0
          ? " (global)"
          : (s.rolling_shutter_bottom_to_top ? " bottom to top" : " top to bottom"),
      s.frame_rate, s.depth_scale, s.depth_noise.model.c_str(), s.common_pixel_sigma_px,
      s.keypoint_sigma_px, s.keypoint_time_sigma_ms);
  const std::string registration =
      s.depth_registered ? ", depth registered"
                         : ", depth not registered (re-projected into the colour camera)";
  char taken[96] = "";
  if (s.colour_time_offset_ms != 0)
    std::snprintf(
        taken, sizeof(taken), ", colour images taken %g ms %s their stamps",
        std::abs(s.colour_time_offset_ms), s.colour_time_offset_ms < 0 ? "before" : "after");
  const char* clock = s.regular_frame_clock ? "" : ", frames timed by their stamps";
  return "sensor '" + s.name + "' (" + source + ", because " + reason + "): " + intrinsics +
         registration + rest + taken + clock;
}

nlohmann::json TSensorChoice::toJson() const
{
  return {
      {"name", sensor.name},
      {"source", source},
      {"reason", reason},
      {"depth_registered", sensor.depth_registered},
      {"rolling_shutter_ms", sensor.signedReadoutMs()},
      {"frame_rate", sensor.frame_rate},
      {"colour_time_offset_ms", sensor.colour_time_offset_ms},
      {"regular_frame_clock", sensor.regular_frame_clock},
      {"common_pixel_sigma_px", sensor.common_pixel_sigma_px},
      {"keypoint_sigma_px", sensor.keypoint_sigma_px},
      {"keypoint_time_sigma_ms", sensor.keypoint_time_sigma_ms},
      {"description", sensor.toIniText()}};
}
}  // namespace roislam::io
