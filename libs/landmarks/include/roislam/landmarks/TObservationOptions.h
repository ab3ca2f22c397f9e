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
 *  - sensor_std_range     metres > 0 (default 0.05): one sigma of the range of a
 *                         ROI centre; dominated by where the ROI's features
 *                         fall on the object rather than by depth noise
 *  - sensor_std_yaw, sensor_std_pitch  radians > 0 (default 0.02, about 10 px
 *                         at f = 517 px, the spread of a ROI centre)
 *  validCovariances is false: these three sigmas apply to every measurement.
 */
struct TObservationOptions : public mrpt::config::CLoadableOptions
{
  std::string sensor_label = "ROI_LANDMARKS";
  mrpt::poses::CPose3D sensor_pose = io::tumSensorPose();
  double min_sensor_distance = 0.1;
  double max_sensor_distance = 8.0;
  double sensor_std_range = 0.05;
  double sensor_std_yaw = 0.02;
  double sensor_std_pitch = 0.02;

  void loadFromConfigFile(
      const mrpt::config::CConfigFileBase& source, const std::string& section) override;
  void saveToConfigFile(
      mrpt::config::CConfigFileBase& target, const std::string& section) const override;
};
}  // namespace roislam::landmarks
