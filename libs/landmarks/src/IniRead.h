/* Private helpers: strict reading of ini values (MRPT's read_double accepts
 * "abc" as 0); errors name the section and key. */
#pragma once

#include <mrpt/config/CConfigFileBase.h>

#include <string>

namespace roislam::landmarks::detail
{
[[noreturn]] void throwBadValue(
    const std::string& section, const std::string& key, const std::string& what);

double readDouble(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section, const std::string& key,
    double defaultValue);
int readInt(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section, const std::string& key,
    int defaultValue);
bool readBool(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section, const std::string& key,
    bool defaultValue);
std::string readString(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section, const std::string& key,
    const std::string& defaultValue);

/** Throws "[section] key: must be <what> (got v)" unless ok. */
void require(
    bool ok, const std::string& section, const std::string& key, double value,
    const std::string& what);
}  // namespace roislam::landmarks::detail
