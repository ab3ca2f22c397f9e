// CRgbdSimulator::TOptions: the [RgbdSimulator] ini section, read strictly
// (every value must parse completely, unknown keys are errors), and checked.
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/system/string_utils.h>
#include <roislam/common/IniRead.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iomanip>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "LensDistortion.h"
#include "roislam/sim/CRgbdSimulator.h"

namespace roislam::sim
{
namespace
{
std::string fmtDouble(double v)
{
  std::ostringstream o;
  o << std::setprecision(17) << v;
  return o.str();
}

/** Strict reader: every value must parse completely; unknown keys are errors. */
class CKeyReader
{
 public:
  CKeyReader(const mrpt::config::CConfigFileBase& cfg, const std::string& section)
      : m_cfg(cfg), m_sec(section)
  {
  }

  template <class T>
  void get(const std::string& key, T& value)
  {
    m_known.insert(key);
    if (!m_cfg.keyExists(m_sec, key))
      return;
    const std::string s = mrpt::system::trim(m_cfg.read_string(m_sec, key, ""));
    if (!parse(s, value))
      throw std::invalid_argument(
          "[" + m_sec + "] " + key + ": cannot parse '" + s + "' as " + typeName(value));
  }

  void rejectUnknownKeys() const
  {
    std::vector<std::string> keys;
    m_cfg.getAllKeys(m_sec, keys);
    for (const auto& k : keys)
      if (!m_known.count(k))
        throw std::invalid_argument("[" + m_sec + "] " + k + ": unknown key");
  }

 private:
  // The text rules are common's (common/IniRead.h); the policy (a present
  // key must hold a value) is this reader's.
  template <typename T>
  static bool assign(const std::optional<T>& parsed, T& v)
  {
    if (parsed)
      v = *parsed;
    return parsed.has_value();
  }
  static bool parse(const std::string& s, double& v) { return assign(common::parseDouble(s), v); }
  static bool parse(const std::string& s, unsigned& v)
  {
    return assign(common::parseUnsigned(s), v);
  }
  static bool parse(const std::string& s, bool& v) { return assign(common::parseBool(s), v); }
  static bool parse(const std::string& s, std::string& v)
  {
    v = s;
    return !s.empty();
  }
  static const char* typeName(double) { return "a number"; }
  static const char* typeName(unsigned) { return "a non-negative integer"; }
  static const char* typeName(bool) { return "a boolean (true|false)"; }
  static const char* typeName(const std::string&) { return "a non-empty string"; }

  const mrpt::config::CConfigFileBase& m_cfg;
  std::string m_sec;
  std::set<std::string> m_known;
};
using TOptions = CRgbdSimulator::TOptions;

/** Throws "[section] key: what". */
struct TKeyError
{
  const std::string& section;
  [[noreturn]] void operator()(const std::string& key, const std::string& what) const
  {
    throw std::invalid_argument("[" + section + "] " + key + ": " + what);
  }
};

// The checks by concern, in the order validate() runs them (the first
// failing key is the one reported).

void validateSequence(const TOptions& o, const TKeyError& fail)
{
  if (o.scene != "textured" && o.scene != "featureless")
    fail("scene", "'" + o.scene + "' is not textured|featureless");
  if (o.frames < 2)
    fail("frames", "must be >= 2");
  if (o.layout != "tum" && o.layout != "7scenes")
    fail("layout", "'" + o.layout + "' is not tum|7scenes");
  if (o.layout == "7scenes" && o.cameraYUp)
    fail("layout", "7scenes publishes optical-frame poses: camera_y_up must be false");
  if (!(o.fps > 0 && o.fps <= 1000))
    fail("fps", "must be in (0, 1000]");
  if (!(std::abs(o.depthTimeOffset) < 0.02))
    fail("depth_time_offset", "must be within +-0.02 s");
  if (!(o.stampDelay >= 0 && o.stampDelay < 0.02))
    fail("stamp_delay", "must be in [0, 0.02) s");
  if (o.stampDelay > 0 && o.layout != "tum")
    fail("stamp_delay", "needs layout = tum (7-Scenes' layout has no stamps)");
  if (!(std::abs(o.depthRadialBias) <= 0.2))
    fail("depth_radial_bias", "must be within +-0.2");
  if (!(o.rollingShutterMs >= 0 && o.rollingShutterMs * 1e-3 <= 1.0 / o.fps))
    fail("rolling_shutter_ms", "must be in [0, frame period]");
  if (!(o.exposureMs >= 0 && o.exposureMs * 1e-3 <= 1.0 / o.fps))
    fail("exposure_ms", "must be in [0, frame period]");
  if (o.exposureSamples < 3 || o.exposureSamples > 63 || o.exposureSamples % 2 == 0)
    fail("exposure_samples", "must be odd, in [3, 63]");
  if (!(o.commonShiftPx >= 0 && o.commonShiftPx <= 10))
    fail("common_shift_px", "must be in [0, 10]");
}

/** A pinhole of the image's size: its keys are prefix + fx, fy, cx, cy. */
void validatePinhole(
    const TOptions& o, const std::string& prefix, double fx, double fy, double cx, double cy,
    const TKeyError& fail)
{
  if (!(fx > 0))
    fail(prefix + "fx", "must be > 0");
  if (!(fy > 0))
    fail(prefix + "fy", "must be > 0");
  if (!(cx >= 0 && cx <= o.width))
    fail(prefix + "cx", "must lie inside the image");
  if (!(cy >= 0 && cy <= o.height))
    fail(prefix + "cy", "must lie inside the image");
}

void validateColourCamera(const TOptions& o, const TKeyError& fail)
{
  if (o.width < 16 || o.width > 4096)
    fail("width", "must be in [16, 4096]");
  if (o.height < 16 || o.height > 4096)
    fail("height", "must be in [16, 4096]");
  validatePinhole(o, "", o.fx, o.fy, o.cx, o.cy, fail);
  const auto dist = detail::parseDistortion(o.colourDist);
  if (!dist)
    fail("colour_dist", "'" + o.colourDist + "' is not [k1 k2 p1 p2 k3]");
  if (detail::isZero(*dist))
    return;
  if (o.commonShiftPx > 0)
    fail("colour_dist", "a distorted colour image cannot take common_shift_px as well");
  try
  {
    detail::makeDistortionMap(*dist, o.width, o.height, o.fx, o.fy, o.cx, o.cy, 1);
  }
  catch (const std::invalid_argument& e)
  {
    fail("colour_dist", e.what());
  }
}

void validateDepthNoise(const TOptions& o, const TKeyError& fail)
{
  if (!(o.minDepth >= 0))
    fail("min_depth", "must be >= 0");
  if (!(o.maxDepth > o.minDepth && o.maxDepth <= 65535 / CRgbdSimulator::kDepthScale))
    fail("max_depth", "must be > min_depth and <= 13.1 (16-bit PNG range)");
  if (!(o.depthNoiseA >= 0))
    fail("depth_noise_a", "must be >= 0");
  if (!(o.depthNoiseB >= 0))
    fail("depth_noise_b", "must be >= 0");
  if (!(o.edgeJumpRatio > 0))
    fail("edge_jump_ratio", "must be > 0");
  if (o.noiseModel != "kinect" && o.noiseModel != "disparity")
    fail("noise_model", "'" + o.noiseModel + "' is not kinect|disparity");
  if (!(o.disparityBf > 0))
    fail("disparity_bf", "must be > 0");
  if (!(o.disparityStepsPerPx > 0))
    fail("disparity_steps_per_px", "must be > 0");
  if (!(o.disparityNoiseSteps >= 0))
    fail("disparity_noise_steps", "must be >= 0");
  if (!(o.lateralSigmaPx >= 0 && o.lateralSigmaPx <= 5))
    fail("lateral_sigma_px", "must be in [0, 5]");
}

void validateDepthCamera(const TOptions& o, const TKeyError& fail)
{
  validatePinhole(o, "depth_", o.depthFx, o.depthFy, o.depthCx, o.depthCy, fail);
  try
  {
    mrpt::poses::CPose3D p;
    p.fromString(o.depthPoseInColour);
  }
  catch (const std::exception&)
  {
    fail("depth_pose_in_colour", "'" + o.depthPoseInColour + "' is not [x y z yaw pitch roll]");
  }
}

void validateRendering(const TOptions& o, const TKeyError& fail)
{
  if (!(o.rgbNoiseStd >= 0 && o.rgbNoiseStd <= 64))
    fail("rgb_noise_std", "must be in [0, 64]");
  if (o.supersampling < 1 || o.supersampling > 4)
    fail("supersampling", "must be in [1, 4]");
  if (!(o.texelsPerMetre >= 50 && o.texelsPerMetre <= 3000))
    fail("texels_per_metre", "must be in [50, 3000]");
}

void validatePath(const TOptions& o, const TKeyError& fail)
{
  if (!(o.pathTranslationAmplitude >= 0 && o.pathTranslationAmplitude <= 0.6))
    fail("path_translation_amplitude", "must be in [0, 0.6] (the room is small)");
  for (auto [k, v] :
       {std::pair{"path_yaw_amplitude_deg", o.pathYawAmplitudeDeg},
        std::pair{"path_pitch_amplitude_deg", o.pathPitchAmplitudeDeg},
        std::pair{"path_roll_amplitude_deg", o.pathRollAmplitudeDeg}})
    if (!(v >= 0 && v <= 45))
      fail(k, "must be in [0, 45]");
  if (!(o.maxLinearSpeed > 0))
    fail("max_linear_speed", "must be > 0");
  if (!(o.maxAngularSpeedDeg > 0))
    fail("max_angular_speed_deg", "must be > 0");
}
}  // namespace

// ---------------------------------------------------------------- TOptions

void CRgbdSimulator::TOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section)
{
  CKeyReader r(cfg, section);
  r.get("scene", scene);
  r.get("furniture", furniture);
  r.get("layout", layout);
  r.get("frames", frames);
  r.get("seed", seed);
  r.get("texture_seed", textureSeed);
  r.get("noise", noise);
  r.get("fps", fps);
  r.get("base_timestamp", baseTimestamp);
  r.get("depth_time_offset", depthTimeOffset);
  r.get("stamp_delay", stampDelay);
  r.get("rolling_shutter_ms", rollingShutterMs);
  r.get("exposure_ms", exposureMs);
  r.get("exposure_samples", exposureSamples);
  r.get("common_shift_px", commonShiftPx);
  r.get("width", width);
  r.get("height", height);
  r.get("fx", fx);
  r.get("fy", fy);
  r.get("cx", cx);
  r.get("cy", cy);
  r.get("colour_dist", colourDist);
  r.get("min_depth", minDepth);
  r.get("max_depth", maxDepth);
  r.get("depth_noise_a", depthNoiseA);
  r.get("depth_noise_b", depthNoiseB);
  r.get("depth_noise_z0", depthNoiseZ0);
  r.get("edge_jump_ratio", edgeJumpRatio);
  r.get("noise_model", noiseModel);
  r.get("disparity_bf", disparityBf);
  r.get("disparity_steps_per_px", disparityStepsPerPx);
  r.get("disparity_noise_steps", disparityNoiseSteps);
  r.get("lateral_sigma_px", lateralSigmaPx);
  r.get("depth_registered", depthRegistered);
  r.get("depth_fx", depthFx);
  r.get("depth_fy", depthFy);
  r.get("depth_cx", depthCx);
  r.get("depth_cy", depthCy);
  r.get("depth_pose_in_colour", depthPoseInColour);
  r.get("depth_radial_bias", depthRadialBias);
  r.get("camera_y_up", cameraYUp);
  r.get("rgb_noise_std", rgbNoiseStd);
  r.get("supersampling", supersampling);
  r.get("texels_per_metre", texelsPerMetre);
  r.get("path_translation_amplitude", pathTranslationAmplitude);
  r.get("path_yaw_amplitude_deg", pathYawAmplitudeDeg);
  r.get("path_pitch_amplitude_deg", pathPitchAmplitudeDeg);
  r.get("path_roll_amplitude_deg", pathRollAmplitudeDeg);
  r.get("max_linear_speed", maxLinearSpeed);
  r.get("max_angular_speed_deg", maxAngularSpeedDeg);
  r.rejectUnknownKeys();
  validate(section);
}

void CRgbdSimulator::TOptions::saveToConfigFile(
    mrpt::config::CConfigFileBase& cfg, const std::string& section) const
{
  auto w = [&](const char* k, const std::string& v) { cfg.write(section, k, v); };
  auto wd = [&](const char* k, double v) { w(k, fmtDouble(v)); };
  w("scene", scene);
  w("furniture", furniture ? "true" : "false");
  w("layout", layout);
  w("frames", std::to_string(frames));
  w("seed", std::to_string(seed));
  w("texture_seed", std::to_string(textureSeed));
  w("noise", noise ? "true" : "false");
  wd("fps", fps);
  wd("base_timestamp", baseTimestamp);
  wd("depth_time_offset", depthTimeOffset);
  wd("stamp_delay", stampDelay);
  wd("rolling_shutter_ms", rollingShutterMs);
  wd("exposure_ms", exposureMs);
  w("exposure_samples", std::to_string(exposureSamples));
  wd("common_shift_px", commonShiftPx);
  w("width", std::to_string(width));
  w("height", std::to_string(height));
  wd("fx", fx);
  wd("fy", fy);
  wd("cx", cx);
  wd("cy", cy);
  w("colour_dist", colourDist);
  wd("min_depth", minDepth);
  wd("max_depth", maxDepth);
  wd("depth_noise_a", depthNoiseA);
  wd("depth_noise_b", depthNoiseB);
  wd("depth_noise_z0", depthNoiseZ0);
  wd("edge_jump_ratio", edgeJumpRatio);
  w("noise_model", noiseModel);
  wd("disparity_bf", disparityBf);
  wd("disparity_steps_per_px", disparityStepsPerPx);
  wd("disparity_noise_steps", disparityNoiseSteps);
  wd("lateral_sigma_px", lateralSigmaPx);
  w("depth_registered", depthRegistered ? "true" : "false");
  wd("depth_fx", depthFx);
  wd("depth_fy", depthFy);
  wd("depth_cx", depthCx);
  wd("depth_cy", depthCy);
  w("depth_pose_in_colour", depthPoseInColour);
  wd("depth_radial_bias", depthRadialBias);
  w("camera_y_up", cameraYUp ? "true" : "false");
  wd("rgb_noise_std", rgbNoiseStd);
  w("supersampling", std::to_string(supersampling));
  wd("texels_per_metre", texelsPerMetre);
  wd("path_translation_amplitude", pathTranslationAmplitude);
  wd("path_yaw_amplitude_deg", pathYawAmplitudeDeg);
  wd("path_pitch_amplitude_deg", pathPitchAmplitudeDeg);
  wd("path_roll_amplitude_deg", pathRollAmplitudeDeg);
  wd("max_linear_speed", maxLinearSpeed);
  wd("max_angular_speed_deg", maxAngularSpeedDeg);
}

void CRgbdSimulator::TOptions::validate(const std::string& section) const
{
  const TKeyError fail{section};
  validateSequence(*this, fail);
  validateColourCamera(*this, fail);
  validateDepthNoise(*this, fail);
  validateDepthCamera(*this, fail);
  validateRendering(*this, fail);
  validatePath(*this, fail);
}
}  // namespace roislam::sim
