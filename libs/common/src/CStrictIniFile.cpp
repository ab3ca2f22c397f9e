#include "roislam/common/CStrictIniFile.h"

#include <roislam/common/ErrorText.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace roislam::common
{
namespace
{
std::string lower(std::string s)
{
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

std::string trim(const std::string& s)
{
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos)
    return {};
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

bool isComment(const std::string& t)
{
  return t.empty() || t[0] == ';' || t[0] == '#' || t.rfind("//", 0) == 0;
}

bool isKeyChar(unsigned char c)
{
  return std::isalnum(c) || c == '_' || c == '.' || c == '-' || c == ':' || c == '/';
}

/** The line as the error shows it: printable, at most 60 characters. */
std::string quoted(const std::string& t)
{
  return "'" + printableExcerpt(t) + "'";
}

/** One logical line: physical lines joined by a trailing '\', with the
 *  number of its first physical line. */
struct TLogicalLine
{
  std::size_t number = 0;
  std::string text;
};

/** Every ${NAME} in `text` must name an @define above (MRPT throws without
 *  the file otherwise). */
void checkVariables(
    const std::string& text, const std::set<std::string>& defined, const std::string& where)
{
  for (auto open = text.find("${"); open != std::string::npos; open = text.find("${", open + 2))
  {
    const auto close = text.find('}', open);
    if (close == std::string::npos)
      throw std::runtime_error(where + "unterminated '${'");
    const std::string name = text.substr(open + 2, close - open - 2);
    if (!defined.count(name))
      throw std::runtime_error(where + "unknown variable ${" + name + "} (no @define above)");
  }
}

std::vector<TLogicalLine> logicalLines(const std::string& text, const std::string& label)
{
  std::vector<TLogicalLine> out;
  std::istringstream in(text);
  std::string line;
  std::size_t number = 0;
  bool continued = false;
  while (std::getline(in, line))
  {
    ++number;
    if (!line.empty() && line.back() == '\r')
      line.pop_back();
    if (line.find('\0') != std::string::npos)
      throw std::runtime_error(
          label + ":" + std::to_string(number) + ": NUL byte (not a text file)");
    if (!continued)
      out.push_back({number, std::string()});
    continued = !line.empty() && line.back() == '\\';
    out.back().text += continued ? line.substr(0, line.size() - 1) : line;
  }
  return out;
}
}  // namespace

std::map<std::pair<std::string, std::string>, std::size_t> CStrictIniFile::check(
    const std::string& text, const std::string& label)
{
  std::map<std::pair<std::string, std::string>, std::size_t> keys;
  std::string section;
  bool inSection = false;
  std::set<std::string> defined;
  for (const auto& [number, raw] : logicalLines(text, label))
  {
    const std::string where = label + ":" + std::to_string(number) + ": ";
    const std::string t = trim(raw);
    if (isComment(t))
      continue;
    if (t[0] == '[')
    {
      const auto close = t.find(']');
      const std::string name = close == std::string::npos ? "" : trim(t.substr(1, close - 1));
      const std::string rest = close == std::string::npos ? "" : trim(t.substr(close + 1));
      if (close == std::string::npos || name.empty() || name.find('[') != std::string::npos ||
          !isComment(rest))
        throw std::runtime_error(where + "malformed section header " + quoted(t));
      section = lower(name);
      inSection = true;
      continue;
    }
    if (t.rfind("@define", 0) == 0)
    {
      std::istringstream ss(t.substr(7));
      std::string name;
      if (t.size() > 7 && (t[7] == ' ' || t[7] == '\t') && (ss >> name))
      {
        checkVariables(t, defined, where);
        defined.insert(name);
        continue;
      }
      throw std::runtime_error(where + "malformed @define (expected '@define NAME value')");
    }
    const auto eq = t.find('=');
    const std::string key = eq == std::string::npos ? "" : trim(t.substr(0, eq));
    const bool keyOk =
        !key.empty() &&
        std::all_of(key.begin(), key.end(), [](unsigned char c) { return isKeyChar(c); });
    if (!keyOk)
      throw std::runtime_error(
          where + "expected a comment, [section] or key = value, got " + quoted(t));
    if (!inSection)
      throw std::runtime_error(where + "key '" + key + "' outside any [section]");
    checkVariables(t, defined, where);
    const auto [it, inserted] = keys.emplace(std::make_pair(section, lower(key)), number);
    if (!inserted)
      throw std::runtime_error(
          where + "duplicate key '" + key + "' (first given on line " + std::to_string(it->second) +
          ")");
  }
  return keys;
}

CStrictIniFile::CStrictIniFile(const std::string& text, const std::string& label, int)
    : mrpt::config::CConfigFileMemory(), m_label(label), m_keyLines(check(text, label))
{
  try
  {
    setContent(text);  // MRPT's preprocessing ($eval{}, $env{}) may still object
  }
  catch (const std::exception& e)
  {
    throw std::runtime_error(label + ": " + oneLineError(e.what()));
  }
}

CStrictIniFile CStrictIniFile::fromText(const std::string& text, const std::string& label)
{
  return CStrictIniFile(text, label, 0);
}

namespace
{
std::string readWholeFile(const std::string& file)
{
  std::ifstream in(file, std::ios::binary);
  if (!std::filesystem::is_regular_file(file) || !in)
    throw std::runtime_error("ini " + file + ": cannot open");
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad())
    throw std::runtime_error("ini " + file + ": read error");
  return ss.str();
}
}  // namespace

CStrictIniFile::CStrictIniFile(const std::string& file)
    : CStrictIniFile(readWholeFile(file), file, 0)
{
}

std::optional<std::size_t> CStrictIniFile::lineOf(
    const std::string& section, const std::string& key) const
{
  const auto it = m_keyLines.find({lower(section), lower(key)});
  if (it == m_keyLines.end())
    return std::nullopt;
  return it->second;
}
}  // namespace roislam::common
