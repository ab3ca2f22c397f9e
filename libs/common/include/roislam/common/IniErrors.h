/* One error format for bad ini values across all TOptions loaders, so that a
 * user always sees which section and key to fix.
 */
#pragma once

#include <string>

namespace roislam::common
{
/** Throws std::invalid_argument "[<section>] <key>: <why>". */
[[noreturn]] void throwBadIniKey(
    const std::string& section, const std::string& key, const std::string& why);
}  // namespace roislam::common
