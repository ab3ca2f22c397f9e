#include "roislam/landmarks/CObservationProcessor.h"

#include <mrpt/system/datetime.h>

#include <cmath>
#include <limits>

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
  return finish(m_tracker.process(frame, cameraPose), frame.camera);
}

CObservationProcessor::TOutput CObservationProcessor::processRegion(const TRegion& region)
{
  TFrameResult r;
  r.frame = region.frame;
  r.timestamp = region.timestamp;
  r.roi = region.box;
  r.features = region.frameFeatures ? static_cast<int>(region.frameFeatures->size()) : 0;
  r.roiFeatures = static_cast<int>(region.features.size());
  r.depthMean = r.depthMedian = r.rigidRms = std::numeric_limits<double>::quiet_NaN();
  r.roiPosition = region.position;
  m_tracker.identify(region, r);
  return finish(std::move(r), region.camera);
}

CObservationProcessor::TOutput CObservationProcessor::finish(
    TFrameResult result, const mrpt::img::TCamera& camera)
{
  std::vector<std::pair<int32_t, mrpt::math::TPoint3D>> seen;
  // A recall's point is carried by its 3-D alignment; one measured from few
  // pairs is left out (min_rigid_pairs). New landmarks define their point.
  const bool supported = result.newLandmark || result.rigidInliers >= m_options.min_rigid_pairs;
  if (result.status == ERoiStatus::Landmark && result.landmarkPosition && supported)
    seen.emplace_back(result.landmarkId, *result.landmarkPosition);
  TOutput out;
  out.observation =
      makeObservation(seen, camera, result.timestamp, m_options.sensor_pose, m_options);
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
  obs->validCovariances = true;
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
    // Depth-noise model: the landmark's spread plus k z^2 (z = depth).
    const double depthNoise = options.range_std_per_m2 * optical.z * optical.z;
    m.covariance(0, 0) =
        options.sensor_std_range * options.sensor_std_range + depthNoise * depthNoise;
    m.covariance(1, 1) = options.sensor_std_yaw * options.sensor_std_yaw;
    m.covariance(2, 2) = options.sensor_std_pitch * options.sensor_std_pitch;
    obs->sensedData.push_back(m);
  }
  return obs;
}

}  // namespace roislam::landmarks
