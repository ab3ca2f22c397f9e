/* MRPT's EKF-SLAM (mrpt::slam::CRangeBearingKFSLAM: 6-DoF robot, 3-D
 * landmarks) run over a kf-slam rawlog of (CActionCollection, CSensoryFrame)
 * pairs, as MRPT's kf-slam app runs it: the same class, configured by the
 * same call (loadOptions) from the same ini sections ([RangeBearingKFSLAM],
 * [RangeBearingKFSLAM_KalmanFilter]), one processActionObservation() per
 * pair. Used by CKfSlamSession (roi-landmarks --kf-slam).
 *
 * Why not the kf-slam executable or KFSLAMApp: both write the robot path
 * only as one robot_pose file per step, and only together with the full
 * state covariance of that step (full_cov_NNNNN.txt, SAVE_LOG_FREQUENCY
 * drives both): (7 + 3 L)^2 numbers per frame for L landmarks, 21 MB for
 * fr1/rpy's 250 frames and 27 landmarks, several GB for full sequences with
 * a few hundred. The integration test
 * runs the installed kf-slam on the same rawlog and ini and checks that its
 * robot_pose files are this class's path.
 *
 * MRPT behaviour to know (read in its source, confirmed by running kf-slam
 * 2.5.8): the filter holds the robot at the origin, skipping predictions,
 * until its map has a landmark, so its frame is the robot's at the first
 * frame with a measurement; measurements carrying a landmark ID are
 * associated by ID (no gating); the measurement noise is the constant
 * std_sensor_range / std_sensor_yaw_deg / std_sensor_pitch_deg of
 * [RangeBearingKFSLAM], not the observations' own covariances.
 */
#pragma once

#include <mrpt/math/TPoint3D.h>
#include <mrpt/poses/CPose3D.h>

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace roislam::kfslam
{
/** What one run of the filter gave. */
struct TKfSlamRun
{
  /** The robot pose after each step (one per rawlog pair), in the filter's
   *  frame, and the timestamp of the step's bearing-range observation. */
  std::vector<mrpt::poses::CPose3D> robotPath;
  std::vector<double> stamps;
  /** Measurements of each step. */
  std::vector<std::size_t> measurements;
  /** First step after which the map holds a landmark (the filter's frame is
   *  the robot's at that step); nullopt when no landmark was ever seen. */
  std::optional<std::size_t> firstLandmarkStep;
  /** The final map: landmark ID -> position in the filter's frame. */
  std::map<int64_t, mrpt::math::TPoint3D> landmarks;
  /** Wall time of the filter steps, seconds. */
  double seconds = 0;
};

class CKfSlamFilter
{
 public:
  /** iniFile: a kf-slam configuration. Throws std::runtime_error "ini <file>:
   *  cannot open" and std::invalid_argument "ini <file>: ..." on a bad option,
   *  among them [MappingApplication] kf_implementation other than the 6-DoF
   *  CRangeBearingKFSLAM (the 2-D filter cannot hold our 3-D camera motion). */
  explicit CKfSlamFilter(const std::string& iniFile);

  /** Runs the filter over a rawlog. Throws std::runtime_error naming the
   *  file when it is missing or corrupt, or names the step the filter
   *  failed at. */
  TKfSlamRun run(const std::string& rawlog) const;

 private:
  std::string m_file;
  std::string m_ini;  //!< the configuration's text
};
}  // namespace roislam::kfslam
