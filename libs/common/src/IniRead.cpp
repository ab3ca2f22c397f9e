#include "roislam/common/IniRead.h"

#include <mrpt/system/string_utils.h>
#include <roislam/common/IniErrors.h>

#include <charconv>
#include <cmath>
#include <limits>
#include <sstream>
#include <system_error>

namespace roislam::common
{
namespace
{
/** from_chars over all of text, after an optional '+' (which it refuses). */
template <typename T>
std::optional<T> parseWhole(const std::string& text)
{
  const char* first = text.data();
  const char* last = text.data() + text.size();
  if (first != last && *first == '+')
    ++first;
  T v{};
  const auto [ptr, ec] = std::from_chars(first, last, v);
  if (first == last || ec != std::errc() || ptr != last)
    return std::nullopt;
  return v;
}

template <typename T, typename Parse>
T readWith(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section, const std::string& key,
    T defaultValue, Parse parse, const char* what)
{
  const std::string s = readString(cfg, section, key, "");
  if (s.empty())
    return defaultValue;
  const auto v = parse(s);
  if (!v)
    throwBadIniKey(section, key, std::string("not ") + what + ": '" + s + "'");
  return *v;
}
}  // namespace

std::optional<double> parseNumber(const std::string& text)
{
  return parseWhole<double>(text);
}

std::optional<double> parseDouble(const std::string& text)
{
  const auto v = parseNumber(text);
  if (!v || !std::isfinite(*v))
    return std::nullopt;
  return v;
}

std::optional<int> parseInt(const std::string& text)
{
  return parseWhole<int>(text);
}

std::optional<unsigned> parseUnsigned(const std::string& text)
{
  if (!text.empty() && text[0] == '-')
    return std::nullopt;
  const auto v = parseWhole<unsigned long long>(text);
  if (!v || *v > std::numeric_limits<uint32_t>::max())
    return std::nullopt;
  return static_cast<unsigned>(*v);
}

std::optional<bool> parseBool(const std::string& text)
{
  const std::string s = mrpt::system::lowerCase(text);
  if (s == "true" || s == "1" || s == "yes" || s == "on")
    return true;
  if (s == "false" || s == "0" || s == "no" || s == "off")
    return false;
  return std::nullopt;
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
  return readWith(cfg, section, key, defaultValue, parseDouble, "a number");
}

int readInt(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section, const std::string& key,
    int defaultValue)
{
  return readWith(cfg, section, key, defaultValue, parseInt, "an integer");
}

bool readBool(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section, const std::string& key,
    bool defaultValue)
{
  return readWith(cfg, section, key, defaultValue, parseBool, "a boolean");
}

void require(
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
