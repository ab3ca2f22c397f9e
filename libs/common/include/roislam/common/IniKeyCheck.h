/* Strict ini checking shared by the apps: a key in one of our sections that
 * no TOptions reads is almost always a typo that would otherwise be silently
 * ignored (MRPT's loaders read with defaults). Used by roi-landmarks and
 * reusable by the SLAM app.
 */
#pragma once

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/config/CLoadableOptions.h>

#include <string>
#include <vector>

namespace roislam::common
{
/** The keys that options.saveToConfigFile(cfg, section) writes into
 *  keysSection (default: section itself), i.e. the keys that
 *  options.loadFromConfigFile(cfg, section) understands there (for TOptions
 *  whose save and load are symmetric, as STYLE.md asks). keysSection names
 *  another section for options that save sub-components under fixed section
 *  names (the front end's [RoiDetector], [FeatureExtractor], ...). */
std::vector<std::string> knownIniKeys(
    const mrpt::config::CLoadableOptions& options, const std::string& section = "Options",
    const std::string& keysSection = "");

/** Throws std::runtime_error "ini <fileLabel>: [<section>] unknown key '<key>'"
 *  for the first key of `section` in cfg that is not in knownKeys (case
 *  insensitive, as MRPT's ini reader). A missing section is fine. */
void checkIniKeys(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section,
    const std::vector<std::string>& knownKeys, const std::string& fileLabel);
}  // namespace roislam::common
