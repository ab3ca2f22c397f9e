/* Trajectory files in the TUM benchmark format:
 * `timestamp tx ty tz qx qy qz qw` per line, '#' comments. Used by the SLAM
 * app (output), the evaluation library and the simulator (ground truth).
 */
#pragma once

#include <mrpt/poses/CPose3D.h>

#include <string>
#include <vector>

namespace roislam::io
{
struct TPoseStamped
{
  double timestamp = 0;
  mrpt::poses::CPose3D pose;
};
using TTrajectory = std::vector<TPoseStamped>;

/** Reads a TUM trajectory. Separators: spaces, commas or tabs; '#' comments
 *  and blank lines are ignored; lines with a NaN or an all-zero quaternion are
 *  skipped (as the benchmark scripts do). The result is sorted by timestamp.
 *  Throws std::runtime_error "<file>:<line>: ..." on a malformed line and
 *  "<file>: cannot open" when unreadable. */
TTrajectory loadTumTrajectory(const std::string& file);

/** Writes a TUM trajectory (full double precision, unit quaternion with
 *  qw >= 0), through a temporary file renamed on success. Throws on failure. */
void saveTumTrajectory(
    const std::string& file, const TTrajectory& trajectory, const std::string& headerComment = "");
}  // namespace roislam::io
