#include <roislam/frontend/SensorNoise.h>

namespace roislam::frontend
{
void applySensorNoise(TRgbdOdometryOptions& o, const io::TSensorDescription& sensor)
{
  o.depth_noise = sensor.depth_noise;
  o.common_pixel_sigma_px = sensor.common_pixel_sigma_px;
  o.keypoint_sigma_px = sensor.keypoint_sigma_px;
  o.keypoint_time_sigma_ms = sensor.keypoint_time_sigma_ms;
}
}  // namespace roislam::frontend
