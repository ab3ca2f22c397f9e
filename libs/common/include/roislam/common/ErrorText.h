/* One-line text of an exception for our error messages. MRPT exceptions span
 * many lines ("==== MRPT exception ====", "Message: ...", location, call
 * stack); we keep the (last) "Message:" text, else the first non-blank line.
 * Used wherever an MRPT or OpenCV error is wrapped into ours.
 */
#pragma once

#include <string>

namespace roislam::common
{
std::string oneLineError(const std::string& what);
}  // namespace roislam::common
