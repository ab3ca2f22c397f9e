#include "roislam/common/IniRead.h"

#include <roislam/common/IniErrors.h>

#include <algorithm>
#include <cctype>
#include <sstream>
#include <stdexcept>

namespace roislam::common
{
namespace
{
std::string trim(const std::string& s)
{
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos)
    return {};
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}
}  // namespace

std::string readString(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section, const std::string& key,
    const std::string& defaultValue)
{
  if (!cfg.keyExists(section, key))
    return defaultValue;
  return trim(cfg.read_string(section, key, defaultValue));
}

double readDouble(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section, const std::string& key,
    double defaultValue)
{
  const std::string s = readString(cfg, section, key, "");
  if (s.empty())
    return defaultValue;
  try
  {
    std::size_t used = 0;
    const double v = std::stod(s, &used);
    if (used != s.size())
      throw std::invalid_argument(s);
    return v;
  }
  catch (const std::exception&)
  {
    throwBadIniKey(section, key, "not a number '" + s + "'");
  }
}

int readInt(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section, const std::string& key,
    int defaultValue)
{
  const std::string s = readString(cfg, section, key, "");
  if (s.empty())
    return defaultValue;
  try
  {
    std::size_t used = 0;
    const int v = std::stoi(s, &used);
    if (used != s.size())
      throw std::invalid_argument(s);
    return v;
  }
  catch (const std::exception&)
  {
    throwBadIniKey(section, key, "not an integer '" + s + "'");
  }
}

bool readBool(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section, const std::string& key,
    bool defaultValue)
{
  std::string s = readString(cfg, section, key, "");
  if (s.empty())
    return defaultValue;
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  if (s == "true" || s == "1" || s == "yes" || s == "on")
    return true;
  if (s == "false" || s == "0" || s == "no" || s == "off")
    return false;
  throwBadIniKey(section, key, "not a boolean '" + s + "'");
}

void requireIni(
    bool ok, const std::string& section, const std::string& key, double value,
    const std::string& what)
{
  if (ok)
    return;
  std::ostringstream os;
  os << "must be " << what << " (got " << value << ")";
  throwBadIniKey(section, key, os.str());
}
}  // namespace roislam::common
