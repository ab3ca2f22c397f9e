/* roi-landmarks --kf-slam: EKF-SLAM on ROI landmarks with MRPT's kf-slam.
 * Per frame (addFrame): our front end's odometry (CRgbdOdometry, no back
 * end) gives the robot's motion with its covariance (COdometryIncrements) as
 * a CActionRobotMovement3D, and the frame's landmark observation (from
 * CObservationProcessor, landmark IDs from our database) goes into a
 * CSensoryFrame; the pair is appended to <outputDir>/kf-slam.rawlog, which
 * the stock command `kf-slam kf-slam-roi.ini kf-slam.rawlog` also runs on.
 * finish() runs MRPT's EKF on that rawlog (CKfSlamFilter) and writes into
 * <outputDir>/kf-slam/:
 *  - trajectory.txt  the EKF's camera path (TUM, one pose per frame; frames
 *                    before the first landmark keep the odometry's poses,
 *                    KfSlamPath.h)
 *  - odometry.txt    the odometry alone (TUM)
 *  - landmarks.txt   the EKF's map: "id x y z" in the trajectory's world
 *  - measurements.txt every measurement of the rawlog: stamp, landmark ID,
 *                    range, yaw, pitch and their sigmas (the consistency
 *                    checks of the README read it with ground truth)
 *                    (as the filter gets them: CMeasurementConditioner)
 *  - motions.txt     every action: stamp, robot motion (x y z yaw pitch
 *                    roll) and its 6x6 covariance
 * and, with ground truth, <outputDir>/kf-slam.landmarks_gt.txt, the
 * reference landmark positions kf-slam's ground_truth_file reads for its
 * error report. It returns the "kf_slam" object of summary.json.
 */
#pragma once

#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/poses/CPose3D.h>
#include <roislam/frontend/CRgbdOdometry.h>
#include <roislam/io/CRawlogWriter.h>
#include <roislam/io/TRGBDFrame.h>
#include <roislam/io/TSensorDescription.h>
#include <roislam/io/TumTrajectory.h>
#include <roislam/kfslam/CKfSlamFilter.h>
#include <roislam/kfslam/CMeasurementConditioner.h>
#include <roislam/kfslam/COdometryIncrements.h>
#include <roislam/kfslam/KfSlamPath.h>
#include <roislam/kfslam/TKfSlamOptions.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace roislam::kfslam
{
class CKfSlamSession
{
 public:
  struct TSetup
  {
    TKfSlamOptions options;
    /** Folder that relative paths of the options are relative to. */
    std::string iniDir;
    /** sensorLocationOnRobot of the observations ([ObservationProcessor] sensor_pose). */
    mrpt::poses::CPose3D sensorPose;
    /** Where the files are written, and where they end up (the paths
     *  summary() reports; empty: outputDir). They differ when the app
     *  writes into a staging folder renamed at the end (COutputFolder). */
    std::string outputDir, finalOutputDir;
    /** Extractor overrides (roi-landmarks --feature / --max-features). */
    std::optional<features::EFeatureType> feature;
    std::optional<int> maxFeatures;
    /** The sensor the source was opened with: its readout
     *  (frameReadoutMs(), unless front_end_ini sets [FrontEnd]
     *  rolling_shutter_ms) and its noise facts (frontend::applySensorNoise)
     *  go to the front end, as in roi-graphslam. None: a global shutter and
     *  the front end's defaults. */
    std::optional<io::TSensorDescription> sensor;
  };

  /** Loads the kf-slam ini and the front end (errors name the file and key)
   *  and opens the rawlog. */
  explicit CKfSlamSession(const TSetup& setup);

  /** The front end's options of [KfSlam] front_end_ini (relative to iniDir),
   *  with the extractor overrides; throws naming the file or key. */
  static frontend::CRgbdOdometry::TOptions frontEndOptions(const TSetup& setup);

  /** One frame: odometry, then the (action, sensory frame) pair. Frames in
   *  order; observation is the frame's (its timestamp is the step's). */
  void addFrame(
      const io::TRGBDFrame& frame, const mrpt::obs::CObservationBearingRange& observation);

  /** Commits the rawlog, runs the EKF, writes the outputs and evaluates both
   *  trajectories against gt when given (sorted by stamp). */
  nlohmann::json finish(const std::optional<io::TTrajectory>& gt);

  /** The files, for the caller's messages: the rawlog where it is written,
   *  or (final) where it ends up (TSetup::finalOutputDir). */
  std::string rawlogFile(bool final = false) const;
  std::string kfSlamIni() const { return m_kfSlamIni; }

 private:
  nlohmann::json evaluate(
      const io::TTrajectory& gt, const io::TTrajectory& ekf, const io::TTrajectory& odometry,
      const TKfSlamRun& run);
  /** Appends the step's measurements and motion to the text logs. */
  void logStep(
      const mrpt::obs::CObservationBearingRange& observation,
      const mrpt::poses::CPose3DPDFGaussian& motion);
  void writeOutputs(
      const io::TTrajectory& ekf, const io::TTrajectory& odometry, const TKfSlamRun& run) const;

  TSetup m_setup;
  std::string m_kfSlamIni;
  CKfSlamFilter m_filter;
  frontend::CRgbdOdometry m_odometry;
  COdometryIncrements m_increments;
  CMeasurementConditioner m_conditioner;
  std::unique_ptr<io::CRawlogWriter> m_rawlog;
  /** Per frame: the odometry's robot pose and the stamp. */
  std::vector<mrpt::poses::CPose3D> m_odometryRobot;
  std::vector<double> m_stamps;
  std::map<int64_t, TFirstSight> m_firstSights;
  std::optional<double> m_firstMeasurementStamp;
  std::size_t m_measurements = 0;
  /** measurements.txt and motions.txt being built (written by finish()). */
  std::ostringstream m_measurementLog, m_motionLog;
};
}  // namespace roislam::kfslam
