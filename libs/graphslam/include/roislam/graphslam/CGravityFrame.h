/* Chooses the gravity-up frame a run's pictures are drawn in (map.bt,
 * scene.3Dscene, snapshot.png): +z up, so viewers such as SceneViewer3D and
 * our snapshot show floors at the bottom. The estimate's own world frame is
 * the first camera's optical frame (y down), which every viewer shows on its
 * side. The trajectory files (trajectory.txt, graph.graph) keep that frame.
 *
 * In order of preference:
 *  - ground truth: the ground truth's frame (TUM and rgbd-simul: z up),
 *    through the rigid alignment the ATE evaluation computed
 *    (display = alignment (+) estimate);
 *  - accelerometer: TUM's accelerometer.txt (io/TumAccelerometer.h). Each
 *    sample within kMaxSampleGap of a tracked frame is turned into the world
 *    by that frame's estimated rotation, and the mean is "up". The mean of
 *    the motion's accelerations over a run is its change of velocity over
 *    its duration, small for a hand-held run that starts and ends slowly, so
 *    gravity dominates. Measured on fr1/xyz (150 frames) and fr1/rpy (250
 *    frames) against the ground truth's z: 3.8 and 4.1 degrees with the
 *    ground truth's own rotations (tests/graphslam/CGravityFrame_unittest),
 *    4.6 and 5.7 degrees with our estimate's (big ROI, summary.json
 *    display_frame.accelerometer_vs_ground_truth_deg), so most of it lies
 *    between the Kinect's accelerometer and the motion-capture frame, not in
 *    the estimate; 0.35 degrees on rgbd-simul's loop;
 *    Refused (falling back) with fewer than kMinSamples samples, or when the
 *    mean is below kMinConsistency of the mean magnitude (the readings
 *    disagree: wrong axes, or a broken estimate);
 *  - first camera: its -y axis as up (right for a camera held level).
 * A levelled frame (accelerometer, first camera) has its origin at the first
 * camera and its y axis along the first camera's view, turned level.
 * Used by CSlamOutputWriter.
 */
#pragma once

#include <mrpt/math/TPoint3D.h>
#include <mrpt/poses/CPose3D.h>
#include <roislam/io/TumAccelerometer.h>
#include <roislam/io/TumTrajectory.h>

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace roislam::graphslam
{
class CGravityFrame
{
 public:
  enum class ESource
  {
    GroundTruth,
    Accelerometer,
    FirstCamera
  };

  /** An accelerometer sample counts for the nearest tracked frame within this (s). */
  static constexpr double kMaxSampleGap = 0.05;
  static constexpr std::size_t kMinSamples = 10;
  static constexpr double kMinConsistency = 0.7;

  struct TResult
  {
    ESource source = ESource::FirstCamera;
    /** display = toDisplay (+) (a pose or point in the estimate's world). */
    mrpt::poses::CPose3D toDisplay;
    /** Accelerometer samples used (0 when none). */
    std::size_t accelerometerSamples = 0;
    /** Angle between the accelerometer's up and the ground truth's, when
     *  both are known (degrees). */
    std::optional<double> accelerometerVsGroundTruthDeg;
    /** Why a preferred source was not used (empty when none was skipped). */
    std::string note;

    /** {"up": "ground_truth"|"accelerometer"|"first_camera",
     *   "estimate_to_display": {x,y,z,qx,qy,qz,qw}, "accelerometer_samples",
     *   ["accelerometer_vs_ground_truth_deg"], ["note"]}. */
    nlohmann::json toJson() const;
  };

  /** `estimate`: camera poses (TUM optical convention) in the estimate's
   *  world, in time order; `groundTruthAlignment`: the ATE alignment when the
   *  ground truth is known; `accelerometer`: a loaded log (may be empty).
   *  Never throws on bad data: it falls back and says why in `note`. */
  static TResult choose(
      const io::TTrajectory& estimate,
      const std::optional<mrpt::poses::CPose3D>& groundTruthAlignment,
      const io::TAccelerometerLog& accelerometer);

  /** As choose(), loading the accelerometer log from a file when given; a
   *  file that cannot be read is a fallback with its one-line error in `note`. */
  static TResult choose(
      const io::TTrajectory& estimate,
      const std::optional<mrpt::poses::CPose3D>& groundTruthAlignment,
      const std::optional<std::string>& accelerometerFile);

  /** Unit "up" in the estimate's world from the accelerometer, and the
   *  number of samples used; nullopt (and why, in `why`) when refused. */
  static std::optional<std::pair<mrpt::math::TVector3D, std::size_t>> upFromAccelerometer(
      const io::TTrajectory& estimate, const io::TAccelerometerLog& accelerometer,
      std::string& why);

  /** The levelled frame for `up` (unit, estimate's world): z along up,
   *  origin at the first camera, y along its view made level. */
  static mrpt::poses::CPose3D levelled(
      const io::TTrajectory& estimate, const mrpt::math::TVector3D& up);

  static std::string toString(ESource source);
};
}  // namespace roislam::graphslam
