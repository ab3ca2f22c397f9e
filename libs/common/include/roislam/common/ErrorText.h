/* One-line text of an exception for our error messages. MRPT exceptions span
 * many lines ("==== MRPT exception ====", "Message: ...", location, call
 * stack); we keep the (last) "Message:" text, else the first non-blank line.
 * Used wherever an MRPT or OpenCV error is wrapped into ours.
 */
#pragma once

#include <cstddef>
#include <string>

namespace roislam::common
{
std::string oneLineError(const std::string& what);

/** `text` up to its first newline (all of it without one), as is: for
 *  messages of our own and the libraries' one-liners, where oneLineError's
 *  search for MRPT's "Message:" line is not wanted. */
std::string firstLine(const std::string& text);

/** `text` as an error message may quote it: non-printable bytes (newlines,
 *  control characters, non-ASCII) as '?', at most maxChars then "...". */
std::string printableExcerpt(const std::string& text, std::size_t maxChars = 60);
}  // namespace roislam::common
