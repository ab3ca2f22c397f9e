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

/** The line without its '\r', checked to be text. */
std::string checkedText(std::string line, const std::string& where)
{
  if (!line.empty() && line.back() == '\r')
    line.pop_back();
  if (line.find('\0') != std::string::npos)
    throw std::runtime_error(where + "NUL byte (not a text file)");
  if (!validText(line))
    throw std::runtime_error(where + "control character or invalid UTF-8");
  return line;
}

/** The value without a leading tag ("!tag value" -> "value"). */
std::string withoutTag(std::string value)
{
  if (!value.empty() && value[0] == '!')
  {
    const auto blank = value.find(' ');
    value = blank == std::string::npos ? std::string() : trim(value.substr(blank));
  }
  return value;
}

/** The checker's state from one line to the next: an open flow sequence, a
 *  key waiting for its nested mapping, the mappings open at each indentation. */
class CYamlChecker
{
 public:
  explicit CYamlChecker(const std::string& label) : m_label(label) {}

  void addLine(const std::string& line)
  {
    ++m_n;
    const std::string where = m_label + ":" + std::to_string(m_n) + ": ";
    const std::string body = stripComment(checkedText(line, where));
    if (m_depth > 0)
    {
      continueSequence(body, where);
      return;
    }
    const std::string s = trim(body);
    if (s.empty())
      return;
    const std::size_t indent = body.find_first_not_of(' ');
    if (body[indent] == '\t')
      throw std::runtime_error(where + "tab in indentation (YAML indents with spaces)");
    if (m_ended)
      throw std::runtime_error(where + "content after the end of the document ('...')");
    if (indent == 0 && documentLine(s, where))
      return;
    m_content = true;
    keyValueLine(s, indent, where);
  }

  void finish() const
  {
    if (m_depth > 0)
      throw std::runtime_error(m_label + ":" + std::to_string(m_openLine) + ": '[' never closed");
    if (m_nestedExpected)
      throw noValue();
    if (m_stack.empty())
      throw std::runtime_error(m_label + ": no YAML content");
  }

 private:
  void continueSequence(const std::string& body, const std::string& where)
  {
    // A sequence's continuation lines are indented deeper than its key.
    const auto first = body.find_first_not_of(' ');
    if (first != std::string::npos && first <= m_openIndent)
      throw std::runtime_error(where + "sequence continued without indentation (a ']' missing?)");
    m_depth = flowDepth(body, m_depth, where);
  }

  /** A directive or a document marker ("---", "..."): true when s is one. */
  bool documentLine(const std::string& s, const std::string& where)
  {
    if (s[0] == '%')
    {
      if (m_content || s.rfind("%YAML 1.", 0) != 0)
        throw std::runtime_error(where + "unsupported directive " + quoted(s));
      return true;
    }
    if (s == "---" || s == "...")
    {
      if (s == "---" && m_content)
        throw std::runtime_error(where + "a second document is not supported");
      m_ended = s == "...";
      m_content = true;
      return true;
    }
    return false;
  }

  void keyValueLine(const std::string& s, std::size_t indent, const std::string& where)
  {
    const std::size_t colon = keyColon(s);
    const std::string key = colon == std::string::npos ? "" : trim(s.substr(0, colon));
    if (!plainKey(key))
      throw std::runtime_error(where + "expected 'key: value', got " + quoted(s));
    enterMapping(indent, where);
    const auto [it, inserted] = m_stack.back().keyLines.emplace(key, m_n);
    if (!inserted)
      throw std::runtime_error(
          where + "duplicate key '" + key + "' (first given on line " + std::to_string(it->second) +
          ")");
    checkValue(withoutTag(trim(s.substr(colon + 1))), key, indent, where);
  }

  /** Opens the awaited nested mapping or returns to the one at indent. */
  void enterMapping(std::size_t indent, const std::string& where)
  {
    if (m_nestedExpected && indent <= m_nestedParentIndent)
      throw noValue();
    if (m_nestedExpected)
      m_stack.push_back({indent, {}});
    m_nestedExpected = false;
    while (!m_stack.empty() && indent < m_stack.back().indent)
      m_stack.pop_back();
    if (m_stack.empty())
      m_stack.push_back({indent, {}});
    if (indent != m_stack.back().indent)
      throw std::runtime_error(
          where + "bad indentation (column " + std::to_string(indent + 1) + ", expected " +
          std::to_string(m_stack.back().indent + 1) + ")");
  }

  void checkValue(
      const std::string& value, const std::string& key, std::size_t indent,
      const std::string& where)
  {
    if (value.empty())
    {
      m_nestedExpected = true;
      m_nestedParentIndent = indent;
      m_nestedLine = m_n;
      m_nestedKey = key;
    }
    else if (value[0] == '[')
    {
      m_depth = flowDepth(value, 0, where);
      m_openLine = m_n;
      m_openIndent = indent;
    }
    else
      checkScalar(value, where);
  }

  // "key:" with nothing after must open a mapping on the next lines.
  std::runtime_error noValue() const
  {
    return std::runtime_error(
        m_label + ":" + std::to_string(m_nestedLine) + ": key '" + m_nestedKey + "' has no value");
  }

  std::string m_label;
  std::size_t m_n = 0, m_openLine = 0, m_openIndent = 0;
  int m_depth = 0;
  bool m_content = false, m_ended = false, m_nestedExpected = false;
  std::size_t m_nestedParentIndent = 0, m_nestedLine = 0;
  std::string m_nestedKey;
  std::vector<TMapping> m_stack;
};
}  // namespace

void checkStrictYaml(const std::string& text, const std::string& label)
{
  std::istringstream in(text);
  CYamlChecker checker(label);
  std::string line;
  while (std::getline(in, line))
    checker.addLine(line);
  checker.finish();
}
}  // namespace roislam::common
