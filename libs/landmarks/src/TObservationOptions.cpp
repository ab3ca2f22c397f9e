#include "roislam/landmarks/TObservationOptions.h"

#include "IniRead.h"

namespace roislam::landmarks
{
void TObservationOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& s)
{
  sensor_label = detail::readString(c, s, "sensor_label", sensor_label);
  if (sensor_label.empty())
    detail::throwBadValue(s, "sensor_label", "must not be empty");
  const std::string pose = detail::readString(c, s, "sensor_pose", "");
  if (!pose.empty())
  {
    try
    {
      sensor_pose.fromString(pose);
    }
    catch (const std::exception&)
    {
      detail::throwBadValue(
          s, "sensor_pose", "expected \"[x y z yaw pitch roll]\", got '" + pose + "'");
    }
  }
  min_sensor_distance = detail::readDouble(c, s, "min_sensor_distance", min_sensor_distance);
  max_sensor_distance = detail::readDouble(c, s, "max_sensor_distance", max_sensor_distance);
  sensor_std_range = detail::readDouble(c, s, "sensor_std_range", sensor_std_range);
  range_std_per_m2 = detail::readDouble(c, s, "range_std_per_m2", range_std_per_m2);
  sensor_std_yaw = detail::readDouble(c, s, "sensor_std_yaw", sensor_std_yaw);
  sensor_std_pitch = detail::readDouble(c, s, "sensor_std_pitch", sensor_std_pitch);
  min_rigid_pairs = detail::readInt(c, s, "min_rigid_pairs", min_rigid_pairs);
  detail::require(min_rigid_pairs >= 0, s, "min_rigid_pairs", min_rigid_pairs, ">= 0");
  detail::require(min_sensor_distance >= 0, s, "min_sensor_distance", min_sensor_distance, ">= 0");
  detail::require(
      max_sensor_distance > min_sensor_distance, s, "max_sensor_distance", max_sensor_distance,
      "> min_sensor_distance");
  detail::require(sensor_std_range > 0, s, "sensor_std_range", sensor_std_range, "> 0");
  detail::require(range_std_per_m2 >= 0, s, "range_std_per_m2", range_std_per_m2, ">= 0");
  detail::require(sensor_std_yaw > 0, s, "sensor_std_yaw", sensor_std_yaw, "> 0");
  detail::require(sensor_std_pitch > 0, s, "sensor_std_pitch", sensor_std_pitch, "> 0");
}

void TObservationOptions::saveToConfigFile(
    mrpt::config::CConfigFileBase& c, const std::string& s) const
{
  c.write(s, "sensor_label", sensor_label);
  c.write(s, "sensor_pose", sensor_pose.asString());
  c.write(s, "min_sensor_distance", min_sensor_distance);
  c.write(s, "max_sensor_distance", max_sensor_distance);
  c.write(s, "sensor_std_range", sensor_std_range);
  c.write(s, "range_std_per_m2", range_std_per_m2);
  c.write(s, "sensor_std_yaw", sensor_std_yaw);
  c.write(s, "sensor_std_pitch", sensor_std_pitch);
  c.write(s, "min_rigid_pairs", min_rigid_pairs);
}
}  // namespace roislam::landmarks
