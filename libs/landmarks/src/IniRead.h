/* Private: the strict ini readers (roislam/common/IniRead.h) under the names
 * the landmark pipeline's loaders use. */
#pragma once

#include <roislam/common/IniErrors.h>
#include <roislam/common/IniRead.h>

#include <string>

namespace roislam::landmarks::detail
{
using common::readBool;
using common::readDouble;
using common::readInt;
using common::readString;

[[noreturn]] inline void throwBadValue(
    const std::string& section, const std::string& key, const std::string& what)
{
  common::throwBadIniKey(section, key, what);
}

inline void require(
    bool ok, const std::string& section, const std::string& key, double value,
    const std::string& what)
{
  common::requireIni(ok, section, key, value, what);
}
}  // namespace roislam::landmarks::detail
