#include "roislam/kfslam/TKfSlamOptions.h"

#include <roislam/common/IniErrors.h>
#include <roislam/common/IniRead.h>

namespace roislam::kfslam
{
void TKfSlamOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& s)
{
  kf_slam_ini = common::readString(c, s, "kf_slam_ini", kf_slam_ini);
  front_end_ini = common::readString(c, s, "front_end_ini", front_end_ini);
  odometry_covariance = common::readString(c, s, "odometry_covariance", odometry_covariance);
  odometry_sigma_m = common::readDouble(c, s, "odometry_sigma_m", odometry_sigma_m);
  odometry_sigma_deg = common::readDouble(c, s, "odometry_sigma_deg", odometry_sigma_deg);
  weak_sigma_m = common::readDouble(c, s, "weak_sigma_m", weak_sigma_m);
  weak_sigma_deg = common::readDouble(c, s, "weak_sigma_deg", weak_sigma_deg);
  landmark_rolling_shutter =
      common::readBool(c, s, "landmark_rolling_shutter", landmark_rolling_shutter);
  remeasure_interval_s = common::readDouble(c, s, "remeasure_interval_s", remeasure_interval_s);
  landmark_gate_probability =
      common::readDouble(c, s, "landmark_gate_probability", landmark_gate_probability);
  validate(s);
}

void TKfSlamOptions::saveToConfigFile(mrpt::config::CConfigFileBase& c, const std::string& s) const
{
  c.write(s, "kf_slam_ini", kf_slam_ini);
  c.write(s, "front_end_ini", front_end_ini);
  c.write(s, "odometry_covariance", odometry_covariance);
  c.write(s, "odometry_sigma_m", odometry_sigma_m);
  c.write(s, "odometry_sigma_deg", odometry_sigma_deg);
  c.write(s, "weak_sigma_m", weak_sigma_m);
  c.write(s, "weak_sigma_deg", weak_sigma_deg);
  c.write(s, "landmark_rolling_shutter", landmark_rolling_shutter);
  c.write(s, "remeasure_interval_s", remeasure_interval_s);
  c.write(s, "landmark_gate_probability", landmark_gate_probability);
}

void TKfSlamOptions::validate(const std::string& s) const
{
  if (kf_slam_ini.empty())
    common::throwBadIniKey(s, "kf_slam_ini", "must name the kf-slam configuration");
  if (odometry_covariance != "frontend" && odometry_covariance != "fixed")
    common::throwBadIniKey(
        s, "odometry_covariance", "expected frontend or fixed, got '" + odometry_covariance + "'");
  common::require(odometry_sigma_m >= 0, s, "odometry_sigma_m", odometry_sigma_m, ">= 0");
  common::require(odometry_sigma_deg >= 0, s, "odometry_sigma_deg", odometry_sigma_deg, ">= 0");
  if (odometry_covariance == "fixed" && odometry_sigma_m == 0 && odometry_sigma_deg == 0)
    common::throwBadIniKey(s, "odometry_sigma_m", "odometry_covariance = fixed needs a sigma > 0");
  common::require(weak_sigma_m > 0, s, "weak_sigma_m", weak_sigma_m, "> 0");
  common::require(weak_sigma_deg > 0, s, "weak_sigma_deg", weak_sigma_deg, "> 0");
  common::require(
      remeasure_interval_s >= 0, s, "remeasure_interval_s", remeasure_interval_s, ">= 0");
  common::require(
      landmark_gate_probability >= 0 && landmark_gate_probability < 1, s,
      "landmark_gate_probability", landmark_gate_probability, "in [0, 1)");
}
}  // namespace roislam::kfslam
