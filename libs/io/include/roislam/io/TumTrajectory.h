/* Trajectory files in the TUM benchmark format:
 * `timestamp tx ty tz qx qy qz qw` per line, '#' comments. Used by the SLAM
 * app (output), the evaluation library and the simulator (ground truth).
 */
#pragma once

#include <mrpt/poses/CPose3D.h>

#include <optional>
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

/** What loadTumTrajectory does with a line holding a NaN or a zero quaternion. */
enum class EInvalidPose
{
  /** An error naming file and line (a ground truth with holes is broken). */
  Reject,
  /** Skip the line, as the benchmark scripts do (roi-eval --skip-invalid). */
  Skip
};

/** Reads a TUM trajectory. Separators: spaces, commas or tabs; '#' comments
 *  and blank lines are ignored; a line with a NaN or an all-zero quaternion
 *  is an error unless `invalid` is Skip. The result is sorted by timestamp.
 *  Throws std::runtime_error "<file>:<line>: ..." on a malformed line and
 *  "<file>: cannot open" when unreadable. */
TTrajectory loadTumTrajectory(const std::string& file, EInvalidPose invalid = EInvalidPose::Reject);

/** The pose at time t of a trajectory sorted by timestamp: nullopt when no
 *  stamp lies within maxDifference of t (the TUM tools' association);
 *  otherwise, with interpolate, the interpolation (slerp, linear position)
 *  between the stamps around t, else the nearest stamp's pose. */
std::optional<mrpt::poses::CPose3D> poseAt(
    const TTrajectory& sorted, double t, double maxDifference, bool interpolate = true);

/** Writes a TUM trajectory (full double precision, unit quaternion with
 *  qw >= 0), through a temporary file renamed on success. Throws on failure. */
void saveTumTrajectory(
    const std::string& file, const TTrajectory& trajectory, const std::string& headerComment = "");
}  // namespace roislam::io
