/* A variant of the ROI versions of Tests 2-3: a name, a report label and ini
 * overrides applied to the mode's config file (e.g. [FrontEnd] strict_roi).
 * Built by CExperimentPlan (defaults: "strict" = the dissertation's behaviour,
 * "fallback" = ours) or parsed from roi-bench --variant.
 */
#pragma once

#include <string>
#include <vector>

namespace roislam::bench
{
struct TIniOverride
{
  std::string section, key, value;
};

struct TVariant
{
  std::string name;   //!< [A-Za-z0-9_] only; part of run ids
  std::string label;  //!< shown in the report
  std::vector<TIniOverride> overrides;

  /** Parses "name:Section.key=value[,Section.key=value...]"; the label is the
   *  spec itself. Throws std::invalid_argument quoting the spec when malformed. */
  static TVariant parse(const std::string& spec);
};

/** "strict" ([FrontEnd] strict_roi = true and roi_feature_cap = roi: no
 *  fallback, N features in the ROI, the dissertation's behaviour), "fallback"
 *  (strict_roi = false, roi_feature_cap = image: our default), "roicap"
 *  (fallback with N features in the ROI), "region" (fallback, stage 2 on
 *  the tracking region only: roi_extraction = region, roi_extension_scale =
 *  0.5) and "flow" (fallback, ordinary frames describe their ROI and follow
 *  the rest by optical flow: roi_extraction = flow). */
std::vector<TVariant> defaultVariants();

/** Test 1's: "hue" ([RoiDetector] verify_hue = true: the ROI verified by the
 *  hue detector, the dissertation's proposal). */
std::vector<TVariant> defaultTest1Variants();

/** iniText with each override set: an existing key in its section is replaced,
 *  a missing key is appended to its section, a missing section is appended.
 *  Comments and the other lines are kept. */
std::string applyIniOverrides(const std::string& iniText, const std::vector<TIniOverride>& ov);
}  // namespace roislam::bench
