#include "roislam/io/TSensorDescription.h"

#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/core/bits_math.h>
#include <roislam/common/IniErrors.h>
#include <roislam/common/IniKeyCheck.h>
#include <roislam/common/IniRead.h>
#include <roislam/io/CameraPresets.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace roislam::io
{
namespace
{
const char* kColourSection = "CAMERA_PARAMS";
const char* kDepthSection = "DEPTH_CAMERA_PARAMS";

// The shortest text that reads back as the same double.
std::string exactText(double v)
{
  char buf[64];
  for (int digits : {15, 16, 17})
  {
    std::snprintf(buf, sizeof(buf), "%.*g", digits, v + 0.0);  // + 0.0: no "-0"
    if (std::strtod(buf, nullptr) == v)
      break;
  }
  return buf;
}

// TCamera::saveToConfigFile writes the intrinsics with 5 decimals (fr1's fx
// 517.306408 would come back as 517.30641): its layout, our precision.
void saveCamera(
    const mrpt::img::TCamera& c, const std::string& section, mrpt::config::CConfigFileBase& cfg)
{
  c.saveToConfigFile(section, cfg);
  cfg.write(section, "cx", exactText(c.cx()));
  cfg.write(section, "cy", exactText(c.cy()));
  cfg.write(section, "fx", exactText(c.fx()));
  cfg.write(section, "fy", exactText(c.fy()));
  // As many coefficients as MRPT wrote for the model.
  const std::string written = cfg.read_string(section, "dist", "");
  std::size_t n = 0;
  bool inNumber = false;
  for (const char ch : written)
  {
    const bool part = ch != ' ' && ch != '[' && ch != ']' && ch != ',' && ch != '\t';
    n += part && !inNumber;
    inNumber = part;
  }
  std::string text = "[";
  for (std::size_t i = 0; i < n && i < c.dist.size(); ++i)
    text += (i ? " " : "") + exactText(c.dist[i]);
  cfg.write(section, "dist", text + "]");
}

std::string poseText(const mrpt::poses::CPose3D& p)
{
  return "[" + exactText(p.x()) + " " + exactText(p.y()) + " " + exactText(p.z()) + " " +
         exactText(mrpt::RAD2DEG(p.yaw())) + " " + exactText(mrpt::RAD2DEG(p.pitch())) + " " +
         exactText(mrpt::RAD2DEG(p.roll())) + "]";
}

mrpt::poses::CPose3D parsePose(
    const std::string& text, const std::string& section, const std::string& key)
{
  mrpt::poses::CPose3D p;
  try
  {
    p.fromString(text);
  }
  catch (const std::exception&)
  {
    common::throwBadIniKey(
        section, key, "expected [x y z yaw pitch roll] (m, deg), got '" + text + "'");
  }
  return p;
}

/** The keys of [SensorDescription] and the strict read of each. */
void readScalars(
    TSensorDescription& d, const mrpt::config::CConfigFileBase& cfg, const std::string& s)
{
  auto& n = d.depth_noise;
  d.name = common::readString(cfg, s, "name", d.name);
  d.depth_registered = common::readBool(cfg, s, "depth_registered", d.depth_registered);
  const std::string pose = common::readString(cfg, s, "depth_pose_in_colour", "");
  if (!pose.empty())
    d.depth_pose_in_colour = parsePose(pose, s, "depth_pose_in_colour");
  d.estimate_registration =
      common::readBool(cfg, s, "estimate_registration", d.estimate_registration);
  d.depth_scale = common::readDouble(cfg, s, "depth_scale", d.depth_scale);
  d.rolling_shutter_ms = common::readDouble(cfg, s, "rolling_shutter_ms", d.rolling_shutter_ms);
  const std::string dir = common::readString(
      cfg, s, "rolling_shutter_direction",
      d.rolling_shutter_bottom_to_top ? "bottom_to_top" : "top_to_bottom");
  if (dir != "top_to_bottom" && dir != "bottom_to_top")
    common::throwBadIniKey(
        s, "rolling_shutter_direction",
        "must be top_to_bottom or bottom_to_top (got '" + dir + "')");
  d.rolling_shutter_bottom_to_top = dir == "bottom_to_top";
  d.frame_rate = common::readDouble(cfg, s, "frame_rate", d.frame_rate);
  d.colour_time_offset_ms =
      common::readDouble(cfg, s, "colour_time_offset_ms", d.colour_time_offset_ms);
  d.regular_frame_clock = common::readBool(cfg, s, "regular_frame_clock", d.regular_frame_clock);
  d.common_pixel_sigma_px =
      common::readDouble(cfg, s, "common_pixel_sigma_px", d.common_pixel_sigma_px);
  d.keypoint_sigma_px = common::readDouble(cfg, s, "keypoint_sigma_px", d.keypoint_sigma_px);
  d.keypoint_time_sigma_ms =
      common::readDouble(cfg, s, "keypoint_time_sigma_ms", d.keypoint_time_sigma_ms);
  n.model = common::readString(cfg, s, "depth_noise_model", n.model);
  n.a = common::readDouble(cfg, s, "depth_noise_a", n.a);
  n.b = common::readDouble(cfg, s, "depth_noise_b", n.b);
  n.z0 = common::readDouble(cfg, s, "depth_noise_z0", n.z0);
  n.disparity_bf = common::readDouble(cfg, s, "disparity_bf", n.disparity_bf);
  n.disparity_steps_per_px =
      common::readDouble(cfg, s, "disparity_steps_per_px", n.disparity_steps_per_px);
  n.disparity_noise_steps =
      common::readDouble(cfg, s, "disparity_noise_steps", n.disparity_noise_steps);
  n.lateral_sigma_px = common::readDouble(cfg, s, "lateral_sigma_px", n.lateral_sigma_px);
}
}  // namespace

const char* sensorSection()
{
  return "SensorDescription";
}

double TSensorDescription::TDepthNoise::sigma(double z) const
{
  if (model == "kinect")
    return a + b * (z - z0) * (z - z0);
  if (model == "disparity")
  {
    const double noise = disparity_noise_steps, quantisation = 1 / std::sqrt(12.0);
    const double sigmaSteps = std::sqrt(noise * noise + quantisation * quantisation);
    return z * z / disparity_bf * sigmaSteps / disparity_steps_per_px;
  }
  return 0;
}

double TSensorDescription::signedReadoutMs() const
{
  return rolling_shutter_bottom_to_top ? -rolling_shutter_ms : rolling_shutter_ms;
}

double TSensorDescription::frameReadoutMs() const
{
  // Rows flipped by the frame sources are read out in the opposite order.
  return colour.fy() < 0 ? -signedReadoutMs() : signedReadoutMs();
}

void TSensorDescription::validate(const std::string& s) const
{
  // A negative focal length is a camera whose pixel axis runs against its
  // optical axis (ICL-NUIM's fy < 0; CameraAxes.h); zero is no camera.
  const auto cameraOk = [](const mrpt::img::TCamera& c)
  {
    return c.ncols > 0 && c.nrows > 0 && std::isfinite(c.fx()) && std::isfinite(c.fy()) &&
           c.fx() != 0 && c.fy() != 0;
  };
  if (!cameraOk(colour))
    common::throwBadIniKey(
        kColourSection, "resolution", "needs positive resolution and non-zero fx, fy");
  if (!depth_registered && !cameraOk(depth))
    common::throwBadIniKey(
        kDepthSection, "resolution",
        "needs positive resolution and non-zero fx, fy (depth_registered = false)");
  // depth_pose_in_colour is a rigid motion between the two optical frames,
  // which exists only when both frames have the same handedness.
  if (!depth_registered &&
      ((colour.fx() < 0) != (depth.fx() < 0) || (colour.fy() < 0) != (depth.fy() < 0)))
    common::throwBadIniKey(
        kDepthSection, "fy",
        "the signs of fx and fy must be those of [CAMERA_PARAMS] (both optical frames in one "
        "axis convention, so that depth_pose_in_colour is a rigid motion)");
  if (name.empty())
    common::throwBadIniKey(s, "name", "must not be empty");
  common::require(depth_scale > 0, s, "depth_scale", depth_scale, "> 0 (units per metre)");
  common::require(frame_rate > 0, s, "frame_rate", frame_rate, "> 0 Hz");
  common::require(
      rolling_shutter_ms >= 0 && rolling_shutter_ms <= 1000 / frame_rate, s, "rolling_shutter_ms",
      rolling_shutter_ms, "in [0, one frame period]");
  common::require(
      std::abs(colour_time_offset_ms) <= 1000 / frame_rate, s, "colour_time_offset_ms",
      colour_time_offset_ms, "within one frame period of 0");
  common::require(
      common_pixel_sigma_px >= 0 && std::isfinite(common_pixel_sigma_px), s,
      "common_pixel_sigma_px", common_pixel_sigma_px, ">= 0 px");
  common::require(
      keypoint_sigma_px >= 0 && std::isfinite(keypoint_sigma_px), s, "keypoint_sigma_px",
      keypoint_sigma_px, ">= 0 px");
  common::require(
      keypoint_time_sigma_ms >= 0 && keypoint_time_sigma_ms <= 1000 / frame_rate, s,
      "keypoint_time_sigma_ms", keypoint_time_sigma_ms, "in [0, one frame period]");
  const auto& n = depth_noise;
  if (n.model != "kinect" && n.model != "disparity" && n.model != "none")
    common::throwBadIniKey(
        s, "depth_noise_model", "must be kinect, disparity or none (got '" + n.model + "')");
  common::require(n.a >= 0, s, "depth_noise_a", n.a, ">= 0 m");
  common::require(n.b >= 0, s, "depth_noise_b", n.b, ">= 0 1/m");
  common::require(n.z0 >= 0, s, "depth_noise_z0", n.z0, ">= 0 m");
  common::require(n.disparity_bf > 0, s, "disparity_bf", n.disparity_bf, "> 0 m px");
  common::require(
      n.disparity_steps_per_px > 0, s, "disparity_steps_per_px", n.disparity_steps_per_px, "> 0");
  common::require(
      n.disparity_noise_steps >= 0, s, "disparity_noise_steps", n.disparity_noise_steps, ">= 0");
  common::require(n.lateral_sigma_px >= 0, s, "lateral_sigma_px", n.lateral_sigma_px, ">= 0 px");
}

void TSensorDescription::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section)
{
  colour = cameraFromConfig(cfg, kColourSection);
  common::checkIniKeys(cfg, section, common::knownIniKeys(*this, section), "sensor description");
  readScalars(*this, cfg, section);
  if (!depth_registered)
  {
    if (!cfg.sectionExists(kDepthSection))
      common::throwBadIniKey(
          section, "depth_registered",
          std::string("false needs a [") + kDepthSection + "] section (the depth camera)");
    depth = cameraFromConfig(cfg, kDepthSection);
  }
  validate(section);
}

void TSensorDescription::saveToConfigFile(
    mrpt::config::CConfigFileBase& cfg, const std::string& s) const
{
  saveCamera(colour, kColourSection, cfg);
  if (!depth_registered)
    saveCamera(depth, kDepthSection, cfg);
  const auto& n = depth_noise;
  cfg.write(s, "name", name);
  cfg.write(s, "depth_registered", depth_registered);
  cfg.write(s, "depth_pose_in_colour", poseText(depth_pose_in_colour));
  cfg.write(s, "estimate_registration", estimate_registration);
  const auto w = [&](const char* key, double v) { cfg.write(s, key, exactText(v)); };
  w("depth_scale", depth_scale);
  w("rolling_shutter_ms", rolling_shutter_ms);
  cfg.write(
      s, "rolling_shutter_direction",
      std::string(rolling_shutter_bottom_to_top ? "bottom_to_top" : "top_to_bottom"));
  w("frame_rate", frame_rate);
  w("colour_time_offset_ms", colour_time_offset_ms);
  cfg.write(s, "regular_frame_clock", regular_frame_clock);
  w("common_pixel_sigma_px", common_pixel_sigma_px);
  w("keypoint_sigma_px", keypoint_sigma_px);
  w("keypoint_time_sigma_ms", keypoint_time_sigma_ms);
  cfg.write(s, "depth_noise_model", n.model);
  w("depth_noise_a", n.a);
  w("depth_noise_b", n.b);
  w("depth_noise_z0", n.z0);
  w("disparity_bf", n.disparity_bf);
  w("disparity_steps_per_px", n.disparity_steps_per_px);
  w("disparity_noise_steps", n.disparity_noise_steps);
  w("lateral_sigma_px", n.lateral_sigma_px);
}

std::string TSensorDescription::toIniText() const
{
  mrpt::config::CConfigFileMemory cfg;
  saveToConfigFile(cfg, sensorSection());
  return cfg.getContent();
}
}  // namespace roislam::io
