#include "roislam/common/IniErrors.h"

#include <stdexcept>

namespace roislam::common
{
void throwBadIniKey(const std::string& section, const std::string& key, const std::string& why)
{
  throw std::invalid_argument("[" + section + "] " + key + ": " + why);
}
}  // namespace roislam::common
