#include "roislam/landmarks/TPipelineOptions.h"

#include <roislam/common/CStrictIniFile.h>

#include <stdexcept>

#include "IniRead.h"
#include "roislam/common/IniKeyCheck.h"

namespace roislam::landmarks
{
void TTrackerOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& s)
{
  min_depth = detail::readDouble(c, s, "min_depth", min_depth);
  max_depth = detail::readDouble(c, s, "max_depth", max_depth);
  confirm = detail::readBool(c, s, "confirm", confirm);
  max_position_jump = detail::readDouble(c, s, "max_position_jump", max_position_jump);
  detail::require(max_position_jump >= 0, s, "max_position_jump", max_position_jump, ">= 0");
  detail::require(min_depth > 0, s, "min_depth", min_depth, "> 0");
  detail::require(max_depth > min_depth, s, "max_depth", max_depth, "> min_depth");
}

void TTrackerOptions::saveToConfigFile(mrpt::config::CConfigFileBase& c, const std::string& s) const
{
  c.write(s, "min_depth", min_depth);
  c.write(s, "max_depth", max_depth);
  c.write(s, "confirm", confirm);
  c.write(s, "max_position_jump", max_position_jump);
}

namespace
{
template <typename OPTIONS>
void loadSection(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section, OPTIONS& options,
    const std::vector<std::string>& extraKeys, const std::string& fileLabel)
{
  std::vector<std::string> keys = common::knownIniKeys(OPTIONS());
  keys.insert(keys.end(), extraKeys.begin(), extraKeys.end());
  common::checkIniKeys(cfg, section, keys, fileLabel);
  if (!cfg.sectionExists(section))
    return;
  try
  {
    options.loadFromConfigFile(cfg, section);
  }
  catch (const std::exception& e)
  {
    throw std::runtime_error("ini " + fileLabel + ": " + e.what());
  }
}
}  // namespace

void TPipelineOptions::load(const mrpt::config::CConfigFileBase& cfg, const std::string& fileLabel)
{
  // erosions/dilations are only meaningful with preset=custom, so a
  // preset-based save may not write them.
  loadSection(cfg, "RoiDetector", roi, {"erosions", "dilations", "preset"}, fileLabel);
  loadSection(cfg, "FeatureExtractor", features, {}, fileLabel);
  loadSection(cfg, "FeatureMatcher", matcher, {}, fileLabel);
  loadSection(cfg, "HomographyLocator", locator, {}, fileLabel);
  loadSection(cfg, "LandmarkDatabase", database, {}, fileLabel);
  loadSection(cfg, "RoiLandmarks", tracker, {}, fileLabel);
  loadSection(cfg, "LandmarkScoring", scoring, {}, fileLabel);
  loadSection(cfg, "ObservationProcessor", observations, {}, fileLabel);
  loadSection(cfg, "KfSlam", kfSlam, {}, fileLabel);
}

void TPipelineOptions::loadFromFile(const std::string& file)
{
  const common::CStrictIniFile cfg(file);
  load(cfg, file);
}

void TPipelineOptions::save(mrpt::config::CConfigFileBase& cfg) const
{
  roi.saveToConfigFile(cfg, "RoiDetector");
  features.saveToConfigFile(cfg, "FeatureExtractor");
  matcher.saveToConfigFile(cfg, "FeatureMatcher");
  locator.saveToConfigFile(cfg, "HomographyLocator");
  database.saveToConfigFile(cfg, "LandmarkDatabase");
  tracker.saveToConfigFile(cfg, "RoiLandmarks");
  scoring.saveToConfigFile(cfg, "LandmarkScoring");
  observations.saveToConfigFile(cfg, "ObservationProcessor");
  kfSlam.saveToConfigFile(cfg, "KfSlam");
}
}  // namespace roislam::landmarks
