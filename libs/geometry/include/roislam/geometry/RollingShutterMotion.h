/* The rolling-shutter motion model shared by the front end's keypoint
 * rectification (libs/frontend RollingShutter.h) and the kf-slam
 * measurement conditioner (libs/kfslam CMeasurementConditioner): a camera
 * whose rows are read out one after the other sees each row from a
 * slightly different pose while it moves.
 */
#pragma once

#include <roislam/geometry/Rotation.h>

#include <Eigen/Dense>

namespace roislam::geometry
{
/** A point X seen s seconds after the reference (middle) row by a camera
 *  turning at omega (rad/s) and moving at v (m/s), both in its own frame,
 *  carried into the camera at the reference row's time: exp(omega s) X + v s
 *  (constant velocity over the few milliseconds of a readout). */
inline Eigen::Vector3d carryToReferenceRow(
    const Eigen::Vector3d& X, const Eigen::Vector3d& omega, const Eigen::Vector3d& v, double s)
{
  return expSO3(omega * s) * X + v * s;
}
}  // namespace roislam::geometry
