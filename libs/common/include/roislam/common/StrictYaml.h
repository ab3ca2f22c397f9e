/* Strict check of the small YAML subset that calibration files use (ROS
 * camera_info / MRPT TCamera::asYAML), ahead of MRPT's YAML reader: that one
 * keeps the last of two equal keys, and on a syntax error prints libfyaml's
 * diagnostics on stderr and returns an empty document, so the user sees a
 * missing key instead of the broken line.
 *
 * Accepted: "%YAML 1.x" directives and "---" before the content, "..." at the
 * end, comments and blank lines; block mappings "key: value" / "key:" with
 * space indentation (a nested mapping indented deeper than its key, siblings
 * at the same column); values that are plain or quoted scalars, an optional
 * "!!tag", or flow sequences "[a, b, ...]" (which may span lines); a key
 * without a value must open a nested mapping.
 * Anything else, a key repeated in one mapping, or a sequence left open
 * throws std::runtime_error "<label>:<line>: <why>".
 */
#pragma once

#include <string>

namespace roislam::common
{
void checkStrictYaml(const std::string& text, const std::string& label);
}  // namespace roislam::common
