#include "roislam/common/StringLists.h"

#include <mrpt/system/string_utils.h>

namespace roislam::common
{
std::vector<std::string> splitList(const std::string& text)
{
  std::vector<std::string> items, out;
  mrpt::system::tokenize(text, ",", items);
  for (const auto& item : items)
    if (std::string t = mrpt::system::trim(item); !t.empty())
      out.push_back(std::move(t));
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
