/* Whole text files: written through a temporary name renamed on success (a
 * reader never sees a partial file, a failed write leaves none), and read in
 * one go. Used by the apps' outputs and roi-bench.
 */
#pragma once

#include <string>

namespace roislam::common
{
/** Writes `content` to `file` through a temporary name (unique per process
 *  and thread) renamed on success; throws std::runtime_error naming the file
 *  on failure. */
void writeFileAtomically(const std::string& file, const std::string& content);
/** Whole content of a file; throws std::runtime_error "<file>: cannot open". */
std::string readFile(const std::string& file);
}  // namespace roislam::common
