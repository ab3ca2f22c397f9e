#include "roislam/common/IniKeyCheck.h"

#include <mrpt/config/CConfigFileMemory.h>
#include <roislam/common/CStrictIniFile.h>

#include <algorithm>
#include <cctype>
#include <stdexcept>

namespace roislam::common
{
namespace
{
std::string lower(std::string s)
{
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}
}  // namespace

std::vector<std::string> knownIniKeys(const mrpt::config::CLoadableOptions& options)
{
  mrpt::config::CConfigFileMemory mem;
  const std::string section = "S";
  options.saveToConfigFile(mem, section);
  std::vector<std::string> keys;
  mem.getAllKeys(section, keys);
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
    const std::string k = lower(key);
    const bool known = std::any_of(
        knownKeys.begin(), knownKeys.end(), [&](const std::string& s) { return lower(s) == k; });
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
