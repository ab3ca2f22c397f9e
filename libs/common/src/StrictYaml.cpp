#include "roislam/common/StrictYaml.h"

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
  std::string out;
  for (unsigned char c : t.substr(0, 60))
    out += std::isprint(c) ? static_cast<char>(c) : '?';
  return "'" + out + (t.size() > 60 ? "...'" : "'");
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
    else if (c == '[')
      ++depth;
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
  std::size_t n = 0, openLine = 0;
  int depth = 0;
  bool content = false, ended = false, nestedExpected = false;
  std::size_t nestedParentIndent = 0;
  std::vector<TMapping> stack;
  while (std::getline(in, line))
  {
    ++n;
    const std::string where = label + ":" + std::to_string(n) + ": ";
    if (!line.empty() && line.back() == '\r')
      line.pop_back();
    if (line.find('\0') != std::string::npos)
      throw std::runtime_error(where + "NUL byte (not a text file)");
    const std::string body = stripComment(line);
    if (depth > 0)
    {
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
    if (nestedExpected && indent > nestedParentIndent)
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
    }
    else if (value[0] == '[')
    {
      depth = flowDepth(value, 0, where);
      openLine = n;
    }
    else
      checkScalar(value, where);
  }
  if (depth > 0)
    throw std::runtime_error(label + ":" + std::to_string(openLine) + ": '[' never closed");
  if (stack.empty())
    throw std::runtime_error(label + ": no YAML content");
}
}  // namespace roislam::common
