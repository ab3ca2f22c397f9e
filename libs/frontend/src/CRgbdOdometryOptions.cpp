// CRgbdOdometry::TOptions (ini load/save/validation) and the enum names.
#include <mrpt/config/CConfigFileBase.h>
#include <roislam/common/IniErrors.h>

#include <cmath>
#include <stdexcept>

#include "roislam/frontend/CRgbdOdometry.h"

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
void CRgbdOdometry::TOptions::loadFromConfigFile(
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
  roi_min_area_fraction = c.read_double(s, "roi_min_area_fraction", roi_min_area_fraction);
  roi_min_aspect = c.read_double(s, "roi_min_aspect", roi_min_aspect);
  roi_extension_scale = c.read_double(s, "roi_extension_scale", roi_extension_scale);
  min_inliers = c.read_int(s, "min_inliers", min_inliers);
  keyframe_translation_m = c.read_double(s, "keyframe_translation_m", keyframe_translation_m);
  keyframe_rotation_deg = c.read_double(s, "keyframe_rotation_deg", keyframe_rotation_deg);
  keyframe_min_inliers = c.read_int(s, "keyframe_min_inliers", keyframe_min_inliers);
  keyframe_min_flow_inlier_share =
      c.read_double(s, "keyframe_min_flow_inlier_share", keyframe_min_flow_inlier_share);
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
  icp_refine_sigma_m = c.read_double(s, "icp_refine_sigma_m", icp_refine_sigma_m);
  icp_decimation = c.read_int(s, "icp_decimation", icp_decimation);
  icp_max_iterations = c.read_int(s, "icp_max_iterations", icp_max_iterations);
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

void CRgbdOdometry::TOptions::saveToConfigFile(
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
  c.write(s, "roi_min_area_fraction", roi_min_area_fraction);
  c.write(s, "roi_min_aspect", roi_min_aspect);
  c.write(s, "roi_extension_scale", roi_extension_scale);
  c.write(s, "min_inliers", min_inliers);
  c.write(s, "keyframe_translation_m", keyframe_translation_m);
  c.write(s, "keyframe_rotation_deg", keyframe_rotation_deg);
  c.write(s, "keyframe_min_inliers", keyframe_min_inliers);
  c.write(s, "keyframe_min_flow_inlier_share", keyframe_min_flow_inlier_share);
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
  c.write(s, "icp_refine_sigma_m", icp_refine_sigma_m);
  c.write(s, "icp_decimation", icp_decimation);
  c.write(s, "icp_max_iterations", icp_max_iterations);
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

void CRgbdOdometry::TOptions::validate(const std::string& s) const
{
  if (min_roi_features < 3)
    common::throwBadIniKey(s, "min_roi_features", "must be >= 3");
  if (min_roi_inliers < 0)
    common::throwBadIniKey(s, "min_roi_inliers", "must be >= 0");
  if (!(max_roi_sigma_m >= 0))
    common::throwBadIniKey(s, "max_roi_sigma_m", "must be >= 0");
  if (!(max_roi_sigma_deg >= 0))
    common::throwBadIniKey(s, "max_roi_sigma_deg", "must be >= 0");
  if (roi_feature_cap != "image" && roi_feature_cap != "roi")
    common::throwBadIniKey(
        s, "roi_feature_cap", "unknown value '" + roi_feature_cap + "' (expected image or roi)");
  if (roi_extraction != "region" && roi_extraction != "image" && roi_extraction != "flow")
    common::throwBadIniKey(
        s, "roi_extraction",
        "unknown value '" + roi_extraction + "' (expected image, region or flow)");
  if (flow_describe_roi != "always" && flow_describe_roi != "when_weak")
    common::throwBadIniKey(
        s, "flow_describe_roi",
        "unknown value '" + flow_describe_roi + "' (expected always or when_weak)");
  if (roi_extraction == "flow" && !keyframe_full_features)
    common::throwBadIniKey(
        s, "roi_extraction",
        "flow follows the keyframes' whole-image features: it needs keyframe_full_features = "
        "true");
  if (!(roi_min_area_fraction >= 0 && roi_min_area_fraction <= 1))
    common::throwBadIniKey(s, "roi_min_area_fraction", "must be in [0, 1]");
  if (!(roi_min_aspect >= 0 && roi_min_aspect <= 1))
    common::throwBadIniKey(s, "roi_min_aspect", "must be in [0, 1]");
  if (!(roi_extension_scale >= 0.25 && roi_extension_scale <= 1))
    common::throwBadIniKey(s, "roi_extension_scale", "must be in [0.25, 1]");
  if (min_inliers < 3)
    common::throwBadIniKey(s, "min_inliers", "must be >= 3");
  if (keyframe_policy != "motion" && keyframe_policy != "overlap")
    common::throwBadIniKey(
        s, "keyframe_policy",
        "unknown value '" + keyframe_policy + "' (expected motion or overlap)");
  if (!(keyframe_min_overlap >= 0 && keyframe_min_overlap < 1))
    common::throwBadIniKey(s, "keyframe_min_overlap", "must be in [0, 1)");
  if (keyframe_place_limit < 0)
    common::throwBadIniKey(s, "keyframe_place_limit", "must be >= 0 (0 = no limit)");
  // With the overlap policy the motion thresholds are optional bounds.
  const bool motionPolicy = keyframe_policy == "motion";
  if (motionPolicy ? !(keyframe_translation_m > 0) : !(keyframe_translation_m >= 0))
    common::throwBadIniKey(
        s, "keyframe_translation_m", motionPolicy ? "must be > 0" : "must be >= 0 (0 = no bound)");
  if (motionPolicy ? !(keyframe_rotation_deg > 0) : !(keyframe_rotation_deg >= 0))
    common::throwBadIniKey(
        s, "keyframe_rotation_deg", motionPolicy ? "must be > 0" : "must be >= 0 (0 = no bound)");
  if (keyframe_min_inliers < 0)
    common::throwBadIniKey(s, "keyframe_min_inliers", "must be >= 0");
  if (!(keyframe_min_flow_inlier_share >= 0 && keyframe_min_flow_inlier_share < 1))
    common::throwBadIniKey(s, "keyframe_min_flow_inlier_share", "must be in [0, 1) (0 = off)");
  if (recent_keyframes < 0)
    common::throwBadIniKey(s, "recent_keyframes", "must be >= 0");
  if (!(ransac_threshold_m > 0))
    common::throwBadIniKey(s, "ransac_threshold_m", "must be > 0");
  if (ransac_max_iterations < 1)
    common::throwBadIniKey(s, "ransac_max_iterations", "must be >= 1");
  if (refine_iterations < 0)
    common::throwBadIniKey(s, "refine_iterations", "must be >= 0");
  if (!(reprojection_threshold_px > 0))
    common::throwBadIniKey(s, "reprojection_threshold_px", "must be > 0");
  if (!(pixel_sigma_px > 0))
    common::throwBadIniKey(s, "pixel_sigma_px", "must be > 0");
  if (!(min_depth_m >= 0))
    common::throwBadIniKey(s, "min_depth_m", "must be >= 0");
  if (!(max_depth_m > min_depth_m))
    common::throwBadIniKey(s, "max_depth_m", "must be > min_depth_m");
  if (!(depth_discontinuity_m >= 0))
    common::throwBadIniKey(s, "depth_discontinuity_m", "must be >= 0");
  // A readout longer than a second is no video camera's (and a typo of s/ms).
  if (!(std::abs(rolling_shutter_ms) <= 1000))
    common::throwBadIniKey(s, "rolling_shutter_ms", "must be in [-1000, 1000]");
  if (!(icp_refine_sigma_m >= 0))
    common::throwBadIniKey(s, "icp_refine_sigma_m", "must be >= 0");
  if (icp_decimation < 1)
    common::throwBadIniKey(s, "icp_decimation", "must be >= 1");
  if (icp_max_iterations < 1)
    common::throwBadIniKey(s, "icp_max_iterations", "must be >= 1");
  if (!(icp_max_distance_m > 0))
    common::throwBadIniKey(s, "icp_max_distance_m", "must be > 0");
  if (icp_min_pairs < 6)
    common::throwBadIniKey(s, "icp_min_pairs", "must be >= 6");
  if (!(constant_velocity_information_scale > 0))
    common::throwBadIniKey(s, "constant_velocity_information_scale", "must be > 0");
}
}  // namespace roislam::frontend
