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
 * What is measured ([ObservationProcessor] landmark_points):
 *  - features: the confirmed ROI landmark's feature points, each a
 *    point landmark with ID pointLandmarkId(roi landmark ID, index of the
 *    feature among the landmark's first-sight features): a new landmark's
 *    features with depth, a recall's feature pairs explained by its 3-D
 *    alignment (TFrameResult::landmarkPoints). Per sighting at most
 *    points_per_sighting: points already measured before first, then new
 *    ones by detector response while the ROI landmark has fewer than
 *    max_points_per_landmark. Why: a ROI landmark is one point whose error
 *    is the same in consecutive frames (its median point moves on the
 *    surface as the ROI's features change) and it leaves the rotation about
 *    it free; its feature points are physical points measured with pixel and
 *    depth noise, and several of them fix the whole pose.
 *  - roi (default): at most one point, the ROI landmark's at
 *    TFrameResult::landmarkPosition (for a recall, the landmark's stored
 *    point mapped into this frame by the 3-D alignment of the match inliers),
 *    with the ROI landmark's ID.
 * Frames without a landmark give an observation with no measurements, so
 * every RGB-D observation has its partner. Each measurement carries its
 * covariance from the noise model of TObservationOptions (validCovariances).
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
#include <map>
#include <optional>
#include <set>
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

  /** Point landmark IDs: roi * kPointIdStride + feature; nullopt when it
   *  does not fit (feature >= kPointIdStride or the ID beyond int32). */
  static constexpr int32_t kPointIdStride = 10000;
  static std::optional<int32_t> pointLandmarkId(int32_t roi, int feature);

  const CRoiLandmarkTracker& tracker() const { return m_tracker; }
  CRoiLandmarkTracker& tracker() { return m_tracker; }

 private:
  TOutput finish(TFrameResult result, const mrpt::img::TCamera& camera);
  /** The point landmarks a sighting measures (rule above); updates the map. */
  std::vector<std::pair<int32_t, mrpt::math::TPoint3D>> selectPoints(const TFrameResult& r);

  TObservationOptions m_options;
  CRoiLandmarkTracker m_tracker;
  /** Per ROI landmark: the feature indices measured so far. */
  std::map<int32_t, std::set<int>> m_measuredPoints;
};
}  // namespace roislam::landmarks
