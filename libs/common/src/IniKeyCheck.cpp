#include "roislam/common/IniKeyCheck.h"

#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/system/string_utils.h>
#include <roislam/common/CStrictIniFile.h>

#include <algorithm>
#include <stdexcept>

namespace roislam::common
{
std::vector<std::string> knownIniKeys(
    const mrpt::config::CLoadableOptions& options, const std::string& section,
    const std::string& keysSection)
{
  mrpt::config::CConfigFileMemory mem;
  options.saveToConfigFile(mem, section);
  std::vector<std::string> keys;
  mem.getAllKeys(keysSection.empty() ? section : keysSection, keys);
  return keys;
}

void checkIniKeys(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section,
    const std::vector<std::string>& knownKeys, const std::string& fileLabel)
{
  if (!cfg.sectionExists(section))
    return;
  std::vector<std::string> present;
  cfg.getAllKeys(section, present);
  for (const auto& key : present)
  {
    const bool known = std::any_of(
        knownKeys.begin(), knownKeys.end(),
        [&](const std::string& s) { return mrpt::system::strCmpI(s, key); });
    if (known)
      continue;
    // Read through CStrictIniFile, the key's line is known.
    const auto* strict = dynamic_cast<const CStrictIniFile*>(&cfg);
    const auto line = strict ? strict->lineOf(section, key) : std::nullopt;
    throw std::runtime_error(
        "ini " + fileLabel + ": [" + section + "] unknown key '" + key + "'" +
        (line ? " (line " + std::to_string(*line) + ")" : std::string()));
  }
}
}  // namespace roislam::common
