/* What the EKF is given of a frame's landmark observation (CKfSlamSession,
 * once per frame, in order): the processor's measurements made consistent
 * with the odometry's geometry and, optionally, thinned in time.
 *
 * Rolling shutter ([KfSlam] landmark_rolling_shutter). The front end carries
 * each keypoint's point to the middle row's time before registering
 * (CRgbdOdometry, rolling_shutter_ms), so its poses are the middle row's
 * camera; the landmark pipeline measures raw points. A landmark point at row
 * fraction f (-0.5 first row .. 0.5 last, its projection's row) was seen
 * s = f * readout seconds after the middle row; it is carried into the
 * middle row's camera as exp(omega s) X + v s, with the camera's velocity
 * (omega, v) of the frame's odometry motion since the previous frame (the
 * velocity the front end corrects its frame with).
 *
 * Re-measure interval ([KfSlam] remeasure_interval_s). A landmark measured
 * in consecutive frames has nearly the same error in each (lag-1
 * autocorrelation 0.7-0.9 on the fr1 excerpts, gone after about 10 frames);
 * a Kalman filter counts such repeats as independent information. Passing a
 * landmark's measurement only when at least this long has passed since its
 * last one gives the filter measurements about as independent as it assumes,
 * instead of inflating every measurement's sigma. A landmark's first
 * measurement always passes.
 *
 * Gate ([KfSlam] landmark_gate_probability). MRPT's filter associates
 * measurements that carry an ID without any gate, and uses the ini's
 * constant sigmas, not the observations' covariances; so a ROI landmark
 * whose point jumped (its features changed, a recall aligned on few pairs)
 * pulls the pose by its whole error. A measurement is passed only when it
 * agrees with the landmark's earlier passed measurements: the component-wise
 * median of their points, placed in the world by the odometry's camera
 * poses and seen from this frame's, predicts range / yaw / pitch, and the
 * innovation's Mahalanobis distance under the measurement's own covariance
 * (the processor's per-frame noise model) times (1 + 1/n), n earlier
 * measurements, plus the odometry's drift since their sightings (the
 * frames' motion covariances, addMotion), is within the chi-square quantile
 * of this probability (3 degrees of freedom). 0 = no gate.
 */
#pragma once

#include <mrpt/img/TCamera.h>
#include <mrpt/math/CMatrixFixed.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/poses/CPose3D.h>

#include <cstdint>
#include <map>
#include <optional>
#include <vector>

namespace roislam::kfslam
{
class CMeasurementConditioner
{
 public:
  /** readoutMs: the front end's signed readout (its rolling_shutter_ms; 0 or
   *  rectify = false: no correction); intervalS >= 0 (0: every frame). */
  CMeasurementConditioner(
      bool rectify, double readoutMs, double intervalS, double gateProbability = 0);

  /** The frame's odometry motion covariance (x y z yaw pitch roll), before
   *  condition() of the same frame: the drift the gate allows for. */
  void addMotion(const mrpt::math::CMatrixDouble66& covariance);

  /** The observation the filter gets for a frame at stamp whose optical
   *  camera pose the odometry gave (nullopt: lost, no correction). */
  mrpt::obs::CObservationBearingRange condition(
      const mrpt::obs::CObservationBearingRange& observation, const mrpt::img::TCamera& camera,
      double stamp, const std::optional<mrpt::poses::CPose3D>& cameraPose);

  /** Measurements dropped by the interval, and by the gate, so far. */
  std::size_t skipped() const { return m_skipped; }
  std::size_t gated() const { return m_gated; }

  /** A measurement (MRPT's camera frame, on the observation's sensor pose)
   *  carried s seconds back along a camera moving with omega (rad/s) and v
   *  (m/s) in the optical frame (the rule above). */
  static void rectify(
      mrpt::obs::CObservationBearingRange::TMeasurement& m, const mrpt::img::TCamera& camera,
      double readoutS, const mrpt::math::TPoint3D& omega, const mrpt::math::TPoint3D& v);

 private:
  bool m_rectify;
  double m_readoutS;
  double m_intervalS;
  std::optional<std::pair<double, mrpt::poses::CPose3D>> m_previous;
  /** A landmark's passed measurements: world points (odometry poses) and
   *  the sums of the cumulative drift variances at their frames. */
  struct TTrack
  {
    std::vector<mrpt::math::TPoint3D> points;
    double driftTSum = 0, driftRSum = 0;
  };
  bool withinGate(
      const mrpt::obs::CObservationBearingRange::TMeasurement& m,
      const mrpt::poses::CPose3D& cameraPose, const TTrack& track) const;

  double m_gateChi2;
  std::map<int32_t, double> m_lastMeasured;
  std::map<int32_t, TTrack> m_tracks;
  /** Cumulative per-axis odometry variance: translation (m^2), rotation (rad^2). */
  double m_driftT = 0, m_driftR = 0;
  std::size_t m_skipped = 0, m_gated = 0;
};
}  // namespace roislam::kfslam
