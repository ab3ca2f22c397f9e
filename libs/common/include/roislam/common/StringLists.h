/* Comma-separated lists as they appear in ini values and command-line flags
 * ("sift, orb"), shared by the experiment plan and the feature benchmark.
 */
#pragma once

#include <string>
#include <vector>

namespace roislam::common
{
/** Splits on ',', trims blanks and tabs, drops empty items
 *  (mrpt::system::tokenize and trim). */
std::vector<std::string> splitList(const std::string& text);

/** Joins with ',' (no blanks): the inverse of splitList for clean items. */
std::string joinList(const std::vector<std::string>& items);
}  // namespace roislam::common
