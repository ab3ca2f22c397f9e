/* Strict reading of ini values. MRPT's read_double / read_int take "abc" as 0
 * and "2.5" as 2; these accept a value only when all of it (trimmed) is a
 * finite number, an integer or a boolean, and otherwise throw
 * std::invalid_argument "[<section>] <key>: not a number: '<text>'" (the
 * throwBadIniKey format). An absent or empty key gives the default. The
 * parse* functions are the text rules alone, for readers with their own
 * policy (the simulator's) and for text files (io's TUM lists and
 * trajectories). Used by the landmarks, the simulator, the trajectory
 * evaluator and io.
 */
#pragma once

#include <mrpt/config/CConfigFileBase.h>

#include <optional>
#include <string>

namespace roislam::common
{
/** All of text is a decimal number, "inf" or "nan" (an optional leading
 *  '+'), as Python's float() of a stripped token. */
std::optional<double> parseNumber(const std::string& text);
/** All of text is a finite decimal number (an optional leading '+'). */
std::optional<double> parseDouble(const std::string& text);
/** All of text is a decimal integer of int's range (an optional sign). */
std::optional<int> parseInt(const std::string& text);
/** All of text is a decimal integer in [0, 2^32). */
std::optional<unsigned> parseUnsigned(const std::string& text);
/** true/false, 1/0, yes/no, on/off in any case. */
std::optional<bool> parseBool(const std::string& text);

/** The trimmed value, or defaultValue when the key is absent. */
std::string readString(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section, const std::string& key,
    const std::string& defaultValue);
double readDouble(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section, const std::string& key,
    double defaultValue);
int readInt(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section, const std::string& key,
    int defaultValue);
bool readBool(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section, const std::string& key,
    bool defaultValue);

/** Throws "[section] key: must be <what> (got <value>)" unless ok. */
void require(
    bool ok, const std::string& section, const std::string& key, double value,
    const std::string& what);
}  // namespace roislam::common
