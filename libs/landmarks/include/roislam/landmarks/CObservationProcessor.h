/* The observation processor of the design, the one path from a frame to its
 * landmark observation: consumes RGB-D frames (TRGBDFrame + optional pose; an
 * MRPT CObservation3DRangeScan becomes one with io::observationToFrame) or
 * regions whose features are already extracted (the SLAM back end's
 * keyframes), runs the ROI landmark pipeline (CRoiLandmarkTracker) and emits
 * the landmarks seen as a standard mrpt::obs::CObservationBearingRange, so
 * rawlogs annotated with it open in RawLogViewer and feed MRPT's
 * landmark-based SLAM (roi-landmarks --kf-slam).
 *
 * Convention (MRPT's, see mrpt::poses::CPose3D::sphericalCoordinates): the
 * measurement is expressed in MRPT's camera frame (x forward, y left, z up),
 * obtained from the optical-frame landmark position (x right, y down,
 * z forward) as (z, -x, -y); range = |p|, yaw = atan2(y, x) about +Z,
 * pitch = -asin(z / range) about +Y (positive = below the optical axis).
 * sensorLocationOnRobot is the pose of that frame on the robot.
 *
 * At most one landmark per frame: the confirmed ROI's, at
 * TFrameResult::landmarkPosition (for a recall, the landmark's stored point
 * mapped into this frame by the 3-D alignment of the match inliers, so
 * repeated observations measure one fixed point). Frames without one give an
 * observation with no measurements, so every RGB-D observation has its
 * partner. Each measurement carries its covariance from the noise model of
 * TObservationOptions (validCovariances).
 */
#pragma once

#include <mrpt/img/TCamera.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/poses/CPose3D.h>
#include <roislam/io/TRGBDFrame.h>
#include <roislam/landmarks/CRoiLandmarkTracker.h>
#include <roislam/landmarks/TFrameResult.h>
#include <roislam/landmarks/TObservationOptions.h>
#include <roislam/landmarks/TRegion.h>

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

namespace roislam::landmarks
{
class CObservationProcessor
{
 public:
  struct TOutput
  {
    TFrameResult result;
    mrpt::obs::CObservationBearingRange::Ptr observation;
  };

  explicit CObservationProcessor(const TPipelineOptions& options = TPipelineOptions());

  /** A TRGBDFrame; the sensor pose on the robot is options.sensor_pose. */
  TOutput process(
      const io::TRGBDFrame& frame,
      const std::optional<mrpt::poses::CPose3D>& cameraPose = std::nullopt);

  /** A region whose features are already extracted (no ROI detection, no
   *  confirmation against the previous frame): recalled or stored as a new
   *  landmark (CRoiLandmarkTracker::identify). Used by the SLAM back end for
   *  its keyframes' ROIs. */
  TOutput processRegion(const TRegion& region);

  /** Builds the observation of landmarks (id, optical-frame position, metres)
   *  seen by a camera with these intrinsics. */
  static mrpt::obs::CObservationBearingRange::Ptr makeObservation(
      const std::vector<std::pair<int32_t, mrpt::math::TPoint3D>>& landmarks,
      const mrpt::img::TCamera& camera, double timestamp, const mrpt::poses::CPose3D& sensorPose,
      const TObservationOptions& options);

  const CRoiLandmarkTracker& tracker() const { return m_tracker; }
  CRoiLandmarkTracker& tracker() { return m_tracker; }

 private:
  TOutput finish(TFrameResult result, const mrpt::img::TCamera& camera);

  TObservationOptions m_options;
  CRoiLandmarkTracker m_tracker;
};
}  // namespace roislam::landmarks
