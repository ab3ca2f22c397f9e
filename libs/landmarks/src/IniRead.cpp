#include "IniRead.h"

#include <mrpt/system/string_utils.h>

#include <sstream>
#include <stdexcept>

namespace roislam::landmarks::detail
{
void throwBadValue(const std::string& section, const std::string& key, const std::string& what)
{
  throw std::invalid_argument("[" + section + "] " + key + ": " + what);
}

std::string readString(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section, const std::string& key,
    const std::string& defaultValue)
{
  if (!cfg.keyExists(section, key))
    return defaultValue;
  return mrpt::system::trim(cfg.read_string(section, key, defaultValue));
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
    throwBadValue(section, key, "not a number '" + s + "'");
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
    throwBadValue(section, key, "not an integer '" + s + "'");
  }
}

bool readBool(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section, const std::string& key,
    bool defaultValue)
{
  const std::string s = mrpt::system::lowerCase(readString(cfg, section, key, ""));
  if (s.empty())
    return defaultValue;
  if (s == "true" || s == "1" || s == "yes" || s == "on")
    return true;
  if (s == "false" || s == "0" || s == "no" || s == "off")
    return false;
  throwBadValue(section, key, "not a boolean '" + s + "'");
}

void require(
    bool ok, const std::string& section, const std::string& key, double value,
    const std::string& what)
{
  if (ok)
    return;
  std::ostringstream os;
  os << "must be " << what << " (got " << value << ")";
  throwBadValue(section, key, os.str());
}
}  // namespace roislam::landmarks::detail
