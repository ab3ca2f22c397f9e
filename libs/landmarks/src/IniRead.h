/* Private: the landmarks' TOptions loaders read their values strictly with
 * common's readers (common/IniRead.h); errors name the section and key. */
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
using common::require;

[[noreturn]] inline void throwBadValue(
    const std::string& section, const std::string& key, const std::string& what)
{
  common::throwBadIniKey(section, key, what);
}
}  // namespace roislam::landmarks::detail
