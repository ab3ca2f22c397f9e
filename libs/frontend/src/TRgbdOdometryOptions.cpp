// TRgbdOdometryOptions (ini load/save/validation) and the enum names.
#include "roislam/frontend/TRgbdOdometryOptions.h"

#include <mrpt/config/CConfigFileBase.h>
#include <roislam/common/IniErrors.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "roislam/frontend/TFrameResult.h"

namespace roislam::frontend
{
std::string toString(ETrackingMethod m)
{
  switch (m)
  {
    case ETrackingMethod::Initial:
      return "initial";
    case ETrackingMethod::Features:
      return "features";
    case ETrackingMethod::RoiFeatures:
      return "roi";
    case ETrackingMethod::Flow:
      return "flow";
    case ETrackingMethod::FullImageFallback:
      return "full_image_fallback";
    case ETrackingMethod::DepthIcp:
      return "depth_icp";
    case ETrackingMethod::ConstantVelocity:
      return "constant_velocity";
    case ETrackingMethod::Lost:
      return "lost";
  }
  return "unknown";
}

EFrontEndMode frontEndModeFromString(const std::string& s)
{
  if (s == "traditional")
    return EFrontEndMode::Traditional;
  if (s == "roi_small")
    return EFrontEndMode::RoiSmall;
  if (s == "roi_big")
    return EFrontEndMode::RoiBig;
  if (s == "roi")
    return EFrontEndMode::Roi;
  throw std::invalid_argument(
      "unknown front-end mode '" + s + "' (expected traditional, roi_small, roi_big or roi)");
}

std::string toString(EFrontEndMode m)
{
  switch (m)
  {
    case EFrontEndMode::Traditional:
      return "traditional";
    case EFrontEndMode::RoiSmall:
      return "roi_small";
    case EFrontEndMode::RoiBig:
      return "roi_big";
    case EFrontEndMode::Roi:
      return "roi";
  }
  return "unknown";
}

std::string toString(EExtension e)
{
  switch (e)
  {
    case EExtension::None:
      return "none";
    case EExtension::WholeImage:
      return "whole_image";
    case EExtension::NoRoi:
      return "no_roi";
    case EExtension::FewRoiFeatures:
      return "few_roi_features";
    case EExtension::RoiFailed:
      return "roi_failed";
    case EExtension::RoiWeak:
      return "roi_weak";
    case EExtension::Keyframe:
      return "keyframe";
    case EExtension::ExpectedKeyframe:
      return "expected_keyframe";
  }
  return "unknown";
}

// ---------------------------------------------------------------- options
void TRgbdOdometryOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& s)
{
  const std::string m = c.read_string(s, "mode", toString(mode));
  try
  {
    mode = frontEndModeFromString(m);
  }
  catch (const std::invalid_argument& e)
  {
    common::throwBadIniKey(s, "mode", e.what());
  }
  strict_roi = c.read_bool(s, "strict_roi", strict_roi);
  min_roi_features = c.read_int(s, "min_roi_features", min_roi_features);
  min_roi_inliers = c.read_int(s, "min_roi_inliers", min_roi_inliers);
  max_roi_sigma_m = c.read_double(s, "max_roi_sigma_m", max_roi_sigma_m);
  max_roi_sigma_deg = c.read_double(s, "max_roi_sigma_deg", max_roi_sigma_deg);
  roi_feature_cap = c.read_string(s, "roi_feature_cap", roi_feature_cap);
  roi_extraction = c.read_string(s, "roi_extraction", roi_extraction);
  flow_describe_roi = c.read_string(s, "flow_describe_roi", flow_describe_roi);
  flow_anchors = c.read_string(s, "flow_anchors", flow_anchors);
  roi_min_area_fraction = c.read_double(s, "roi_min_area_fraction", roi_min_area_fraction);
  roi_min_aspect = c.read_double(s, "roi_min_aspect", roi_min_aspect);
  roi_extension_scale = c.read_double(s, "roi_extension_scale", roi_extension_scale);
  feature_resolution = c.read_string(s, "feature_resolution", feature_resolution);
  min_inliers = c.read_int(s, "min_inliers", min_inliers);
  keyframe_translation_m = c.read_double(s, "keyframe_translation_m", keyframe_translation_m);
  keyframe_rotation_deg = c.read_double(s, "keyframe_rotation_deg", keyframe_rotation_deg);
  keyframe_min_inliers = c.read_int(s, "keyframe_min_inliers", keyframe_min_inliers);
  keyframe_min_inlier_share =
      c.read_double(s, "keyframe_min_inlier_share", keyframe_min_inlier_share);
  keyframe_min_flow_inlier_share =
      c.read_double(s, "keyframe_min_flow_inlier_share", keyframe_min_flow_inlier_share);
  keyframe_on_weak_roi = c.read_bool(s, "keyframe_on_weak_roi", keyframe_on_weak_roi);
  keyframe_policy = c.read_string(s, "keyframe_policy", keyframe_policy);
  keyframe_min_overlap = c.read_double(s, "keyframe_min_overlap", keyframe_min_overlap);
  keyframe_place_limit = c.read_int(s, "keyframe_place_limit", keyframe_place_limit);
  recent_keyframes = c.read_int(s, "recent_keyframes", recent_keyframes);
  ransac_threshold_m = c.read_double(s, "ransac_threshold_m", ransac_threshold_m);
  ransac_max_iterations = c.read_int(s, "ransac_max_iterations", ransac_max_iterations);
  refine_iterations = c.read_int(s, "refine_iterations", refine_iterations);
  reprojection_threshold_px =
      c.read_double(s, "reprojection_threshold_px", reprojection_threshold_px);
  pixel_sigma_px = c.read_double(s, "pixel_sigma_px", pixel_sigma_px);
  scale_aware_weights = c.read_bool(s, "scale_aware_weights", scale_aware_weights);
  min_depth_m = c.read_double(s, "min_depth_m", min_depth_m);
  max_depth_m = c.read_double(s, "max_depth_m", max_depth_m);
  depth_discontinuity_m = c.read_double(s, "depth_discontinuity_m", depth_discontinuity_m);
  rolling_shutter_ms = c.read_double(s, "rolling_shutter_ms", rolling_shutter_ms);
  icp_fallback = c.read_bool(s, "icp_fallback", icp_fallback);
  bridge_previous_frame = c.read_bool(s, "bridge_previous_frame", bridge_previous_frame);
  icp_refine_sigma_m = c.read_double(s, "icp_refine_sigma_m", icp_refine_sigma_m);
  icp_fusion = c.read_string(s, "icp_fusion", icp_fusion);
  icp_min_share = c.read_double(s, "icp_min_share", icp_min_share);
  icp_colour_check = c.read_bool(s, "icp_colour_check", icp_colour_check);
  icp_probe_interval = c.read_int(s, "icp_probe_interval", icp_probe_interval);
  icp_decimation = c.read_int(s, "icp_decimation", icp_decimation);
  icp_max_iterations = c.read_int(s, "icp_max_iterations", icp_max_iterations);
  icp_converged_step_sigma = c.read_double(s, "icp_converged_step_sigma", icp_converged_step_sigma);
  icp_max_distance_m = c.read_double(s, "icp_max_distance_m", icp_max_distance_m);
  icp_min_pairs = c.read_int(s, "icp_min_pairs", icp_min_pairs);
  constant_velocity_information_scale =
      c.read_double(s, "constant_velocity_information_scale", constant_velocity_information_scale);
  keyframe_full_features = c.read_bool(s, "keyframe_full_features", keyframe_full_features);
  keyframe_full_registration =
      c.read_bool(s, "keyframe_full_registration", keyframe_full_registration);
  keyframe_prediction = c.read_bool(s, "keyframe_prediction", keyframe_prediction);
  depth_time_correction = c.read_bool(s, "depth_time_correction", depth_time_correction);

  roi.loadFromConfigFile(c, "RoiDetector");
  extractor.loadFromConfigFile(c, "FeatureExtractor");
  matcher.loadFromConfigFile(c, "FeatureMatcher");
  validate(s);
}

void TRgbdOdometryOptions::saveToConfigFile(
    mrpt::config::CConfigFileBase& c, const std::string& s) const
{
  c.write(s, "mode", toString(mode));
  c.write(s, "strict_roi", strict_roi);
  c.write(s, "min_roi_features", min_roi_features);
  c.write(s, "min_roi_inliers", min_roi_inliers);
  c.write(s, "max_roi_sigma_m", max_roi_sigma_m);
  c.write(s, "max_roi_sigma_deg", max_roi_sigma_deg);
  c.write(s, "roi_feature_cap", roi_feature_cap);
  c.write(s, "roi_extraction", roi_extraction);
  c.write(s, "flow_describe_roi", flow_describe_roi);
  c.write(s, "flow_anchors", flow_anchors);
  c.write(s, "roi_min_area_fraction", roi_min_area_fraction);
  c.write(s, "roi_min_aspect", roi_min_aspect);
  c.write(s, "roi_extension_scale", roi_extension_scale);
  c.write(s, "feature_resolution", feature_resolution);
  c.write(s, "min_inliers", min_inliers);
  c.write(s, "keyframe_translation_m", keyframe_translation_m);
  c.write(s, "keyframe_rotation_deg", keyframe_rotation_deg);
  c.write(s, "keyframe_min_inliers", keyframe_min_inliers);
  c.write(s, "keyframe_min_inlier_share", keyframe_min_inlier_share);
  c.write(s, "keyframe_min_flow_inlier_share", keyframe_min_flow_inlier_share);
  c.write(s, "keyframe_on_weak_roi", keyframe_on_weak_roi);
  c.write(s, "keyframe_policy", keyframe_policy);
  c.write(s, "keyframe_min_overlap", keyframe_min_overlap);
  c.write(s, "keyframe_place_limit", keyframe_place_limit);
  c.write(s, "recent_keyframes", recent_keyframes);
  c.write(s, "ransac_threshold_m", ransac_threshold_m);
  c.write(s, "ransac_max_iterations", ransac_max_iterations);
  c.write(s, "refine_iterations", refine_iterations);
  c.write(s, "reprojection_threshold_px", reprojection_threshold_px);
  c.write(s, "pixel_sigma_px", pixel_sigma_px);
  c.write(s, "scale_aware_weights", scale_aware_weights);
  c.write(s, "min_depth_m", min_depth_m);
  c.write(s, "max_depth_m", max_depth_m);
  c.write(s, "depth_discontinuity_m", depth_discontinuity_m);
  c.write(s, "rolling_shutter_ms", rolling_shutter_ms);
  c.write(s, "icp_fallback", icp_fallback);
  c.write(s, "bridge_previous_frame", bridge_previous_frame);
  c.write(s, "icp_refine_sigma_m", icp_refine_sigma_m);
  c.write(s, "icp_fusion", icp_fusion);
  c.write(s, "icp_min_share", icp_min_share);
  c.write(s, "icp_colour_check", icp_colour_check);
  c.write(s, "icp_probe_interval", icp_probe_interval);
  c.write(s, "icp_decimation", icp_decimation);
  c.write(s, "icp_max_iterations", icp_max_iterations);
  c.write(s, "icp_converged_step_sigma", icp_converged_step_sigma);
  c.write(s, "icp_max_distance_m", icp_max_distance_m);
  c.write(s, "icp_min_pairs", icp_min_pairs);
  c.write(s, "keyframe_full_features", keyframe_full_features);
  c.write(s, "keyframe_full_registration", keyframe_full_registration);
  c.write(s, "keyframe_prediction", keyframe_prediction);
  c.write(s, "depth_time_correction", depth_time_correction);
  c.write(s, "constant_velocity_information_scale", constant_velocity_information_scale);
  roi.saveToConfigFile(c, "RoiDetector");
  extractor.saveToConfigFile(c, "FeatureExtractor");
  matcher.saveToConfigFile(c, "FeatureMatcher");
}

namespace
{
using TOptions = TRgbdOdometryOptions;
using common::throwBadIniKey;

/** A key whose value is one of a few names: "unknown value 'x' (expected a,
 *  b or c)". */
void requireOneOf(
    const std::string& s, const std::string& key, const std::string& value,
    const std::vector<std::string>& names)
{
  for (const auto& n : names)
    if (value == n)
      return;
  std::string expected;
  for (std::size_t i = 0; i < names.size(); ++i)
    expected += (i == 0 ? "" : (i + 1 == names.size() ? " or " : ", ")) + names[i];
  throwBadIniKey(s, key, "unknown value '" + value + "' (expected " + expected + ")");
}

/** The ROI, its region and how frames are described and followed. */
void validateRoi(const TOptions& o, const std::string& s)
{
  if (o.min_roi_features < 3)
    throwBadIniKey(s, "min_roi_features", "must be >= 3");
  if (o.min_roi_inliers < 0)
    throwBadIniKey(s, "min_roi_inliers", "must be >= 0");
  if (!(o.max_roi_sigma_m >= 0))
    throwBadIniKey(s, "max_roi_sigma_m", "must be >= 0");
  if (!(o.max_roi_sigma_deg >= 0))
    throwBadIniKey(s, "max_roi_sigma_deg", "must be >= 0");
  requireOneOf(s, "roi_feature_cap", o.roi_feature_cap, {"image", "roi"});
  requireOneOf(s, "roi_extraction", o.roi_extraction, {"image", "region", "flow"});
  requireOneOf(s, "flow_describe_roi", o.flow_describe_roi, {"always", "when_weak"});
  requireOneOf(s, "flow_anchors", o.flow_anchors, {"features", "corners"});
  requireOneOf(s, "feature_resolution", o.feature_resolution, {"full", "auto"});
  if (o.roi_extraction == "flow" && !o.keyframe_full_features)
    throwBadIniKey(
        s, "roi_extraction",
        "flow follows the keyframes' whole-image features: it needs keyframe_full_features = "
        "true");
  if (!(o.roi_min_area_fraction >= 0 && o.roi_min_area_fraction <= 1))
    throwBadIniKey(s, "roi_min_area_fraction", "must be in [0, 1]");
  if (!(o.roi_min_aspect >= 0 && o.roi_min_aspect <= 1))
    throwBadIniKey(s, "roi_min_aspect", "must be in [0, 1]");
  if (!(o.roi_extension_scale >= 0.25 && o.roi_extension_scale <= 1))
    throwBadIniKey(s, "roi_extension_scale", "must be in [0.25, 1]");
}

/** When a frame becomes a keyframe, and which keyframes it registers with. */
void validateKeyframes(const TOptions& o, const std::string& s)
{
  requireOneOf(s, "keyframe_policy", o.keyframe_policy, {"motion", "overlap"});
  if (!(o.keyframe_min_overlap >= 0 && o.keyframe_min_overlap < 1))
    throwBadIniKey(s, "keyframe_min_overlap", "must be in [0, 1)");
  if (o.keyframe_place_limit < 0)
    throwBadIniKey(s, "keyframe_place_limit", "must be >= 0 (0 = no limit)");
  // With the overlap policy the motion thresholds are optional bounds.
  const bool motionPolicy = o.keyframe_policy == "motion";
  if (motionPolicy ? !(o.keyframe_translation_m > 0) : !(o.keyframe_translation_m >= 0))
    throwBadIniKey(
        s, "keyframe_translation_m", motionPolicy ? "must be > 0" : "must be >= 0 (0 = no bound)");
  if (motionPolicy ? !(o.keyframe_rotation_deg > 0) : !(o.keyframe_rotation_deg >= 0))
    throwBadIniKey(
        s, "keyframe_rotation_deg", motionPolicy ? "must be > 0" : "must be >= 0 (0 = no bound)");
  if (o.keyframe_min_inliers < 0)
    throwBadIniKey(s, "keyframe_min_inliers", "must be >= 0");
  if (!(o.keyframe_min_inlier_share >= 0 && o.keyframe_min_inlier_share < 1))
    throwBadIniKey(s, "keyframe_min_inlier_share", "must be in [0, 1) (0 = off)");
  if (!(o.keyframe_min_flow_inlier_share >= 0 && o.keyframe_min_flow_inlier_share < 1))
    throwBadIniKey(s, "keyframe_min_flow_inlier_share", "must be in [0, 1) (0 = off)");
  if (o.recent_keyframes < 0)
    throwBadIniKey(s, "recent_keyframes", "must be >= 0");
}

/** The registration: RANSAC, its refinement and information, the depth
 *  the features are lifted with. */
void validateRegistration(const TOptions& o, const std::string& s)
{
  if (o.min_inliers < 3)
    throwBadIniKey(s, "min_inliers", "must be >= 3");
  if (!(o.ransac_threshold_m > 0))
    throwBadIniKey(s, "ransac_threshold_m", "must be > 0");
  if (o.ransac_max_iterations < 1)
    throwBadIniKey(s, "ransac_max_iterations", "must be >= 1");
  if (o.refine_iterations < 0)
    throwBadIniKey(s, "refine_iterations", "must be >= 0");
  if (!(o.reprojection_threshold_px > 0))
    throwBadIniKey(s, "reprojection_threshold_px", "must be > 0");
  if (!(o.pixel_sigma_px >= 0) || !std::isfinite(o.pixel_sigma_px))
    throwBadIniKey(s, "pixel_sigma_px", "must be >= 0 (0 = the detector's own)");
  if (!(o.min_depth_m >= 0))
    throwBadIniKey(s, "min_depth_m", "must be >= 0");
  if (!(o.max_depth_m > o.min_depth_m))
    throwBadIniKey(s, "max_depth_m", "must be > min_depth_m");
  if (!(o.depth_discontinuity_m >= 0))
    throwBadIniKey(s, "depth_discontinuity_m", "must be >= 0");
  // A readout longer than a second is no video camera's (and a typo of s/ms).
  if (!(std::abs(o.rolling_shutter_ms) <= 1000))
    throwBadIniKey(s, "rolling_shutter_ms", "must be in [-1000, 1000]");
  if (!(o.constant_velocity_information_scale > 0))
    throwBadIniKey(s, "constant_velocity_information_scale", "must be > 0");
}

/** Depth ICP: the fallback and the refinement of weak registrations. */
void validateIcp(const TOptions& o, const std::string& s)
{
  if (!(o.icp_refine_sigma_m >= 0))
    throwBadIniKey(s, "icp_refine_sigma_m", "must be >= 0");
  requireOneOf(s, "icp_fusion", o.icp_fusion, {"weak", "measured"});
  if (!(o.icp_min_share >= 0))
    throwBadIniKey(s, "icp_min_share", "must be >= 0");
  if (o.icp_probe_interval < 1)
    throwBadIniKey(s, "icp_probe_interval", "must be >= 1");
  if (o.icp_decimation < 1)
    throwBadIniKey(s, "icp_decimation", "must be >= 1");
  if (o.icp_max_iterations < 1)
    throwBadIniKey(s, "icp_max_iterations", "must be >= 1");
  if (!(o.icp_converged_step_sigma >= 0))
    throwBadIniKey(s, "icp_converged_step_sigma", "must be >= 0");
  if (!(o.icp_max_distance_m > 0))
    throwBadIniKey(s, "icp_max_distance_m", "must be > 0");
  if (o.icp_min_pairs < 6)
    throwBadIniKey(s, "icp_min_pairs", "must be >= 6");
}
}  // namespace

void TRgbdOdometryOptions::validate(const std::string& s) const
{
  validateRoi(*this, s);
  validateKeyframes(*this, s);
  validateRegistration(*this, s);
  validateIcp(*this, s);
}
}  // namespace roislam::frontend
