#include "roislam/common/StringLists.h"

#include <sstream>

namespace roislam::common
{
std::vector<std::string> splitList(const std::string& text)
{
  std::vector<std::string> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ','))
  {
    const auto first = item.find_first_not_of(" \t");
    if (first == std::string::npos)
      continue;
    const auto last = item.find_last_not_of(" \t");
    out.push_back(item.substr(first, last - first + 1));
  }
  return out;
}

std::string joinList(const std::vector<std::string>& items)
{
  std::string out;
  for (const auto& s : items)
    out += (out.empty() ? "" : ",") + s;
  return out;
}
}  // namespace roislam::common
