/* Options of CObservationProcessor (how landmark sightings become
 * mrpt::obs::CObservationBearingRange). Separate header so TPipelineOptions
 * can hold it without including the processor.
 */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/poses/CPose3D.h>
#include <roislam/io/ObservationConversion.h>

#include <string>

namespace roislam::landmarks
{
/** ini section "ObservationProcessor":
 *  - sensor_label         string (default ROI_LANDMARKS)
 *  - sensor_pose          "[x y z yaw pitch roll]" (m, degrees): pose on the
 *                         robot of MRPT's camera frame (x forward, y left,
 *                         z up): sensorLocationOnRobot of the observations
 *                         and sensorPose of the annotated rawlog's scans.
 *                         Default "[0 0 0 90 -90 0]": the robot frame is the
 *                         optical camera frame (x right, y down, z forward),
 *                         the convention of every roislam rawlog and of TUM
 *                         poses (io::tumSensorPose()). "[0 0 0 0 0 0]": the
 *                         robot frame is MRPT's camera frame.
 *  - min_sensor_distance  metres >= 0 (default 0.1, = RoiLandmarks min_depth)
 *  - max_sensor_distance  metres > min (default 8.0, = RoiLandmarks max_depth)
 *  Measurement noise (validCovariances = true: each measurement carries its
 *  covariance, diagonal in range, yaw, pitch; sensor_std_* hold the floors
 *  for readers that ignore it):
 *  - sensor_std_range     metres > 0 (default 0.02): the spread of a ROI
 *                         landmark's point from frame to frame (recalled
 *                         points against ground truth on the shared fr1
 *                         excerpts, ORB: 1.5 to 2.4 cm, mostly in depth)
 *  - range_std_per_m2     1/m >= 0 (default 1.425e-3): the depth-noise
 *                         model added in quadrature, sigma_z = k z^2
 *                         (Kinect, Khoshelham & Elberink 2012): 2 mm at
 *                         1.2 m, 1.3 cm at 3 m
 *  - sensor_std_yaw, sensor_std_pitch  radians > 0 (default 0.01, about
 *                         5 px at f = 517 px: measured 0.008 / 0.017 rad
 *                         on fr1 xyz / rpy, where the rolling shutter of
 *                         the fast rotations adds to it)
 *  - min_rigid_pairs      int >= 0 (default 0): a recall gives a measurement
 *                         only when the 3-D alignment that carried the
 *                         landmark's point into the frame kept at least
 *                         this many pairs (a recall located without one has
 *                         0); new landmarks always give theirs
 */
struct TObservationOptions : public mrpt::config::CLoadableOptions
{
  std::string sensor_label = "ROI_LANDMARKS";
  mrpt::poses::CPose3D sensor_pose = io::tumSensorPose();
  double min_sensor_distance = 0.1;
  double max_sensor_distance = 8.0;
  double sensor_std_range = 0.02;
  double range_std_per_m2 = 1.425e-3;
  double sensor_std_yaw = 0.01;
  double sensor_std_pitch = 0.01;
  int min_rigid_pairs = 0;

  void loadFromConfigFile(
      const mrpt::config::CConfigFileBase& source, const std::string& section) override;
  void saveToConfigFile(
      mrpt::config::CConfigFileBase& target, const std::string& section) const override;
};
}  // namespace roislam::landmarks
