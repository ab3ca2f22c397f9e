#include "roislam/common/ErrorText.h"

#include <cctype>

namespace roislam::common
{
std::string oneLineError(const std::string& what)
{
  std::string message, first;
  std::size_t start = 0;
  while (start < what.size())
  {
    auto end = what.find('\n', start);
    if (end == std::string::npos)
      end = what.size();
    std::string line = what.substr(start, end - start);
    const auto b = line.find_first_not_of(" \t");
    if (b != std::string::npos)
    {
      line = line.substr(b);
      if (first.empty())
        first = line;
      if (line.rfind("Message:", 0) == 0)
      {
        const auto m = line.find_first_not_of(" \t", 8);
        message = m == std::string::npos ? std::string() : line.substr(m);
      }
    }
    start = end + 1;
  }
  return message.empty() ? first : message;
}

std::string firstLine(const std::string& text)
{
  return text.substr(0, text.find('\n'));
}

std::string printableExcerpt(const std::string& text, std::size_t maxChars)
{
  std::string out;
  for (unsigned char c : text.substr(0, maxChars))
    out += std::isprint(c) ? static_cast<char>(c) : '?';
  return text.size() > maxChars ? out + "..." : out;
}
}  // namespace roislam::common
