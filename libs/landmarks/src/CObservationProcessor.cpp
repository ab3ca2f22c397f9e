#include "roislam/landmarks/CObservationProcessor.h"

#include <mrpt/system/datetime.h>
#include <roislam/io/ObservationConversion.h>

#include <cmath>

#include "roislam/landmarks/FeatureGeometry.h"

namespace roislam::landmarks
{
CObservationProcessor::CObservationProcessor(const TPipelineOptions& options)
    : m_options(options.observations), m_tracker(options)
{
}

CObservationProcessor::TOutput CObservationProcessor::process(
    const io::TRGBDFrame& frame, const std::optional<mrpt::poses::CPose3D>& cameraPose)
{
  return finish(m_tracker.process(frame, cameraPose), frame, m_options.sensor_pose);
}

CObservationProcessor::TOutput CObservationProcessor::process(
    const mrpt::obs::CObservation3DRangeScan& scan,
    const std::optional<mrpt::poses::CPose3D>& cameraPose)
{
  io::TRGBDFrame frame = frameFromScan(scan);
  frame.index = m_scans++;
  return finish(m_tracker.process(frame, cameraPose), frame, scan.sensorPose);
}

CObservationProcessor::TOutput CObservationProcessor::finish(
    TFrameResult result, const io::TRGBDFrame& frame, const mrpt::poses::CPose3D& pose)
{
  std::vector<std::pair<int32_t, mrpt::math::TPoint3D>> seen;
  if (result.status == ERoiStatus::Landmark && result.landmarkPosition)
    seen.emplace_back(result.landmarkId, *result.landmarkPosition);
  TOutput out;
  out.observation = makeObservation(seen, frame.camera, frame.timestamp, pose, m_options);
  out.result = std::move(result);
  return out;
}

mrpt::obs::CObservationBearingRange::Ptr CObservationProcessor::makeObservation(
    const std::vector<std::pair<int32_t, mrpt::math::TPoint3D>>& landmarks,
    const mrpt::img::TCamera& camera, double timestamp, const mrpt::poses::CPose3D& sensorPose,
    const TObservationOptions& options)
{
  auto obs = mrpt::obs::CObservationBearingRange::Create();
  obs->sensorLabel = options.sensor_label;
  obs->timestamp = mrpt::Clock::fromDouble(timestamp);
  obs->sensorLocationOnRobot = sensorPose;
  obs->minSensorDistance = static_cast<float>(options.min_sensor_distance);
  obs->maxSensorDistance = static_cast<float>(options.max_sensor_distance);
  if (camera.fx() > 0 && camera.fy() > 0 && camera.ncols > 0 && camera.nrows > 0)
  {
    obs->fieldOfView_yaw = static_cast<float>(2 * std::atan(0.5 * camera.ncols / camera.fx()));
    obs->fieldOfView_pitch = static_cast<float>(2 * std::atan(0.5 * camera.nrows / camera.fy()));
  }
  obs->validCovariances = false;
  obs->sensor_std_range = static_cast<float>(options.sensor_std_range);
  obs->sensor_std_yaw = static_cast<float>(options.sensor_std_yaw);
  obs->sensor_std_pitch = static_cast<float>(options.sensor_std_pitch);

  const mrpt::poses::CPose3D origin;
  for (const auto& [id, optical] : landmarks)
  {
    double range, yaw, pitch;
    origin.sphericalCoordinates(opticalToMrptCamera(optical), range, yaw, pitch);
    mrpt::obs::CObservationBearingRange::TMeasurement m;
    m.landmarkID = id;
    m.range = static_cast<float>(range);
    m.yaw = static_cast<float>(yaw);
    m.pitch = static_cast<float>(pitch);
    m.covariance.setZero();
    m.covariance(0, 0) = options.sensor_std_range * options.sensor_std_range;
    m.covariance(1, 1) = options.sensor_std_yaw * options.sensor_std_yaw;
    m.covariance(2, 2) = options.sensor_std_pitch * options.sensor_std_pitch;
    obs->sensedData.push_back(m);
  }
  return obs;
}

io::TRGBDFrame CObservationProcessor::frameFromScan(const mrpt::obs::CObservation3DRangeScan& scan)
{
  return io::observationToFrame(scan, "CObservation3DRangeScan '" + scan.sensorLabel + "'");
}
}  // namespace roislam::landmarks
