#include "roislam/common/StrictYaml.h"

#include <roislam/common/ErrorText.h>

#include <cctype>
#include <map>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace roislam::common
{
namespace
{
std::string trim(const std::string& s)
{
  const auto b = s.find_first_not_of(' ');
  if (b == std::string::npos)
    return {};
  return s.substr(b, s.find_last_not_of(' ') - b + 1);
}

std::string quoted(const std::string& t)
{
  return "'" + printableExcerpt(t) + "'";
}

/** The line without its comment: '#' at the start or after a blank, outside
 *  quotes, starts one. */
std::string stripComment(const std::string& line)
{
  char quote = 0;
  for (std::size_t i = 0; i < line.size(); ++i)
  {
    const char c = line[i];
    if (quote)
    {
      if (c == quote)
        quote = 0;
    }
    else if (c == '"' || c == '\'')
      quote = c;
    else if (c == '#' && (i == 0 || line[i - 1] == ' ' || line[i - 1] == '\t'))
      return line.substr(0, i);
  }
  return line;
}

/** Bracket depth change of a piece of a flow sequence; throws on a ']'
 *  without '[' or on text after the closing bracket. */
int flowDepth(const std::string& text, int depth, const std::string& where)
{
  char quote = 0;
  for (std::size_t i = 0; i < text.size(); ++i)
  {
    const char c = text[i];
    if (quote)
    {
      quote = c == quote ? 0 : quote;
      continue;
    }
    if (c == '"' || c == '\'')
      quote = c;
    else if (c == '[' && depth > 0)
      throw std::runtime_error(where + "nested sequences are not supported");
    else if (c == '[')
      ++depth;
    else if (c == ':' && (i + 1 == text.size() || text[i + 1] == ' '))
      throw std::runtime_error(where + "':' inside a sequence (a ']' missing?)");
    else if (c == '{' || c == '}')
      throw std::runtime_error(where + "flow mappings are not supported");
    else if (c == ']')
    {
      if (--depth < 0)
        throw std::runtime_error(where + "']' without '['");
      if (depth == 0 && !trim(text.substr(i + 1)).empty())
        throw std::runtime_error(where + "text after the closing ']': " + quoted(text));
    }
  }
  if (quote)
    throw std::runtime_error(where + "unterminated quote in a sequence");
  return depth;
}

void checkScalar(const std::string& value, const std::string& where)
{
  const char c = value[0];
  if (c == '"' || c == '\'')
  {
    if (value.size() < 2 || value.back() != c)
      throw std::runtime_error(where + "unterminated quoted value " + quoted(value));
    return;
  }
  if (c == '{')
    throw std::runtime_error(where + "flow mappings are not supported");
  if (c == '&' || c == '*' || c == '|' || c == '>' || c == '@' || c == '`' || c == ']' ||
      (c == '-' && (value.size() == 1 || value[1] == ' ')))
    throw std::runtime_error(where + "unsupported value " + quoted(value));
  if (value.find(": ") != std::string::npos || value.back() == ':')
    throw std::runtime_error(where + "unexpected ':' in value " + quoted(value));
}

/** Printable text: no control characters but tabs, UTF-8 well formed
 *  (libfyaml rejects the rest, printing to stderr). */
bool validText(const std::string& line)
{
  for (std::size_t i = 0; i < line.size(); ++i)
  {
    const auto c = static_cast<unsigned char>(line[i]);
    if (c < 0x80)
    {
      if ((c < 0x20 && c != '\t') || c == 0x7f)
        return false;
      continue;
    }
    const int extra = (c & 0xe0) == 0xc0 ? 1 : (c & 0xf0) == 0xe0 ? 2 : (c & 0xf8) == 0xf0 ? 3 : -1;
    if (extra < 0 || c == 0xc0 || c == 0xc1 || c > 0xf4 ||
        i + static_cast<std::size_t>(extra) >= line.size())
      return false;
    for (int k = 1; k <= extra; ++k)
      if ((static_cast<unsigned char>(line[i + k]) & 0xc0) != 0x80)
        return false;
    i += static_cast<std::size_t>(extra);
  }
  return true;
}

struct TMapping
{
  std::size_t indent = 0;
  std::map<std::string, std::size_t> keyLines;
};

/** Position of the key's ':' (followed by a blank or the end), or npos. */
std::size_t keyColon(const std::string& s)
{
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s[i] == ':' && (i + 1 == s.size() || s[i + 1] == ' '))
      return i;
  return std::string::npos;
}

bool plainKey(const std::string& key)
{
  if (key.empty() || std::string("[]{}\"'!&*?|>%@`#,-").find(key[0]) != std::string::npos)
    return false;
  for (unsigned char c : key)
    if (!std::isprint(c))
      return false;
  return true;
}
}  // namespace

void checkStrictYaml(const std::string& text, const std::string& label)
{
  std::istringstream in(text);
  std::string line;
  std::size_t n = 0, openLine = 0, openIndent = 0;
  int depth = 0;
  bool content = false, ended = false, nestedExpected = false;
  std::size_t nestedParentIndent = 0, nestedLine = 0;
  std::string nestedKey;
  // "key:" with nothing after must open a mapping on the next lines.
  const auto noValue = [&]
  {
    return std::runtime_error(
        label + ":" + std::to_string(nestedLine) + ": key '" + nestedKey + "' has no value");
  };
  std::vector<TMapping> stack;
  while (std::getline(in, line))
  {
    ++n;
    const std::string where = label + ":" + std::to_string(n) + ": ";
    if (!line.empty() && line.back() == '\r')
      line.pop_back();
    if (line.find('\0') != std::string::npos)
      throw std::runtime_error(where + "NUL byte (not a text file)");
    if (!validText(line))
      throw std::runtime_error(where + "control character or invalid UTF-8");
    const std::string body = stripComment(line);
    if (depth > 0)
    {
      // A sequence's continuation lines are indented deeper than its key.
      const auto first = body.find_first_not_of(' ');
      if (first != std::string::npos && first <= openIndent)
        throw std::runtime_error(where + "sequence continued without indentation (a ']' missing?)");
      depth = flowDepth(body, depth, where);
      continue;
    }
    const std::string s = trim(body);
    if (s.empty())
      continue;
    const std::size_t indent = body.find_first_not_of(' ');
    if (body[indent] == '\t')
      throw std::runtime_error(where + "tab in indentation (YAML indents with spaces)");
    if (ended)
      throw std::runtime_error(where + "content after the end of the document ('...')");
    if (indent == 0 && s[0] == '%')
    {
      if (content || s.rfind("%YAML 1.", 0) != 0)
        throw std::runtime_error(where + "unsupported directive " + quoted(s));
      continue;
    }
    if (indent == 0 && (s == "---" || s == "..."))
    {
      if (s == "---" && content)
        throw std::runtime_error(where + "a second document is not supported");
      ended = s == "...";
      content = true;
      continue;
    }
    content = true;
    const std::size_t colon = keyColon(s);
    const std::string key = colon == std::string::npos ? "" : trim(s.substr(0, colon));
    if (!plainKey(key))
      throw std::runtime_error(where + "expected 'key: value', got " + quoted(s));
    if (nestedExpected && indent <= nestedParentIndent)
      throw noValue();
    if (nestedExpected)
      stack.push_back({indent, {}});
    nestedExpected = false;
    while (!stack.empty() && indent < stack.back().indent)
      stack.pop_back();
    if (stack.empty())
      stack.push_back({indent, {}});
    if (indent != stack.back().indent)
      throw std::runtime_error(
          where + "bad indentation (column " + std::to_string(indent + 1) + ", expected " +
          std::to_string(stack.back().indent + 1) + ")");
    const auto [it, inserted] = stack.back().keyLines.emplace(key, n);
    if (!inserted)
      throw std::runtime_error(
          where + "duplicate key '" + key + "' (first given on line " + std::to_string(it->second) +
          ")");
    std::string value = trim(s.substr(colon + 1));
    if (!value.empty() && value[0] == '!')
    {
      const auto blank = value.find(' ');
      value = blank == std::string::npos ? std::string() : trim(value.substr(blank));
    }
    if (value.empty())
    {
      nestedExpected = true;
      nestedParentIndent = indent;
      nestedLine = n;
      nestedKey = key;
    }
    else if (value[0] == '[')
    {
      depth = flowDepth(value, 0, where);
      openLine = n;
      openIndent = indent;
    }
    else
      checkScalar(value, where);
  }
  if (depth > 0)
    throw std::runtime_error(label + ":" + std::to_string(openLine) + ": '[' never closed");
  if (nestedExpected)
    throw noValue();
  if (stack.empty())
    throw std::runtime_error(label + ": no YAML content");
}
}  // namespace roislam::common
