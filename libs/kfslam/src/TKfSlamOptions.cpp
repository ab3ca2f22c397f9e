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
}
}  // namespace roislam::kfslam
