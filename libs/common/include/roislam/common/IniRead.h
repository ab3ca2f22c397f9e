/* Strict reading of ini values: MRPT's read_double accepts "abc" as 0 and
 * read_bool anything that is not "true" as false, so a typo would silently
 * change a setting. These read a key when present, else return the default,
 * and throw std::invalid_argument "[section] key: ..." on a malformed value.
 * Used by the TOptions loaders of the landmark pipeline, the ROI detector and
 * the EKF-SLAM export.
 */
#pragma once

#include <mrpt/config/CConfigFileBase.h>

#include <string>

namespace roislam::common
{
/** The value with surrounding blanks removed, or defaultValue when absent. */
std::string readString(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section, const std::string& key,
    const std::string& defaultValue);
/** A number with nothing after it. */
double readDouble(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section, const std::string& key,
    double defaultValue);
int readInt(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section, const std::string& key,
    int defaultValue);
/** true/1/yes/on or false/0/no/off, any case. */
bool readBool(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section, const std::string& key,
    bool defaultValue);

/** Throws "[section] key: must be <what> (got value)" unless ok. */
void requireIni(
    bool ok, const std::string& section, const std::string& key, double value,
    const std::string& what);
}  // namespace roislam::common
