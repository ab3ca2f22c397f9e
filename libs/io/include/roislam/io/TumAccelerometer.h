/* Accelerometer logs in the TUM benchmark format (accelerometer.txt):
 * `timestamp ax ay az` per line, m/s^2, '#' comments. The TUM Kinect's
 * accelerometer axes are its colour camera's optical axes turned 180 degrees
 * about the optical axis (x left, y up, z forward; measured on fr1/xyz and
 * fr1/rpy against the motion-capture ground truth, see CGravityFrame.h):
 * at rest it reads the specific force, +9.81 m/s^2 along "up".
 * Read by the SLAM outputs to level the map (CGravityFrame), written by
 * rgbd-simul so synthetic sequences have one.
 */
#pragma once

#include <mrpt/math/TPoint3D.h>

#include <string>
#include <vector>

namespace roislam::io
{
struct TAccelerometerSample
{
  double timestamp = 0;
  /** Specific force in the accelerometer's axes, m/s^2. */
  mrpt::math::TVector3D acceleration;
};
using TAccelerometerLog = std::vector<TAccelerometerSample>;

/** The TUM accelerometer's axes from the colour optical frame's: optical =
 *  kinectToOptical(kinect) (a 180-degree turn about z). */
mrpt::math::TVector3D accelerometerToOptical(const mrpt::math::TVector3D& kinect);

/** Reads accelerometer.txt (same text rules as loadTumTrajectory: commas or
 *  tabs as spaces, NaN rows skipped), sorted by stamp. Throws
 *  std::runtime_error "<file>:<line>: ..." on a malformed line and
 *  "<file>: cannot open" when unreadable. */
TAccelerometerLog loadTumAccelerometer(const std::string& file);

/** Writes a log in the same format, through a temporary file renamed on
 *  success. Throws std::runtime_error naming the file on failure. */
void saveTumAccelerometer(
    const std::string& file, const TAccelerometerLog& log, const std::string& headerComment = "");
}  // namespace roislam::io
