#include "roislam/kfslam/CKfSlamSession.h"

#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement3D.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <roislam/common/CStrictIniFile.h>
#include <roislam/common/ErrorText.h>
#include <roislam/common/IniKeyCheck.h>
#include <roislam/common/JsonOrNull.h>
#include <roislam/common/TextFiles.h>
#include <roislam/evaluation/CTrajectoryEvaluator.h>
#include <roislam/frontend/SensorNoise.h>
#include <roislam/io/ObservationConversion.h>

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <sstream>

namespace fs = std::filesystem;

namespace roislam::kfslam
{
namespace
{
std::string resolve(const std::string& path, const std::string& dir)
{
  const fs::path p(path);
  return (p.is_absolute() || dir.empty() ? p : fs::path(dir) / p).lexically_normal().string();
}

/** A bearing-range measurement as a point in MRPT's sensor frame (the
 *  inverse of CPose3D::sphericalCoordinates). */
mrpt::math::TPoint3D sensorPoint(const mrpt::obs::CObservationBearingRange::TMeasurement& m)
{
  const double r = m.range, y = m.yaw, p = m.pitch;
  return {r * std::cos(y) * std::cos(p), r * std::sin(y) * std::cos(p), -r * std::sin(p)};
}

/** Keys a TOptions writes into each section (save and load are symmetric). */
std::vector<std::string> keysOf(
    const mrpt::config::CLoadableOptions& o, const std::string& saveSection,
    const std::string& section)
{
  mrpt::config::CConfigFileMemory mem;
  o.saveToConfigFile(mem, saveSection);
  std::vector<std::string> keys;
  mem.getAllKeys(section, keys);
  return keys;
}
}  // namespace

frontend::CRgbdOdometry::TOptions CKfSlamSession::frontEndOptions(const TSetup& setup)
{
  frontend::CRgbdOdometry::TOptions o;
  // The readout is a camera fact (the sensor description's); an older
  // front-end ini that sets it still wins.
  bool readoutFromIni = false;
  if (!setup.options.front_end_ini.empty())
  {
    const std::string file = resolve(setup.options.front_end_ini, setup.iniDir);
    if (!fs::is_regular_file(file))
      throw std::runtime_error("[KfSlam] front_end_ini: " + file + ": cannot open");
    const common::CStrictIniFile cfg(file);
    for (const std::string s : {"FrontEnd", "RoiDetector", "FeatureExtractor", "FeatureMatcher"})
      common::checkIniKeys(cfg, s, keysOf(o, "FrontEnd", s), file);
    try
    {
      o.loadFromConfigFile(cfg, "FrontEnd");
      readoutFromIni = cfg.keyExists("FrontEnd", "rolling_shutter_ms");
    }
    catch (const std::exception& e)
    {
      throw std::runtime_error("ini " + file + ": " + common::firstLine(e.what()));
    }
  }
  if (!readoutFromIni)
    o.rolling_shutter_ms = setup.sensor ? setup.sensor->frameReadoutMs() : 0.0;
  if (setup.sensor)
    frontend::applySensorNoise(o, *setup.sensor);
  if (setup.feature)
    o.extractor.feature_type = *setup.feature;
  if (setup.maxFeatures)
    o.extractor.max_features = *setup.maxFeatures;
  o.validate();
  return o;
}

CKfSlamSession::CKfSlamSession(const TSetup& setup)
    : m_setup(setup),
      m_kfSlamIni(resolve(setup.options.kf_slam_ini, setup.iniDir)),
      m_filter(m_kfSlamIni),
      m_odometry(frontEndOptions(setup)),
      m_increments(setup.options, setup.sensorPose),
      m_conditioner(
          setup.options.landmark_rolling_shutter, m_odometry.options().rolling_shutter_ms,
          setup.options.remeasure_interval_s, setup.options.landmark_gate_probability)
{
  std::error_code ec;
  fs::create_directories(setup.outputDir, ec);
  m_rawlog = std::make_unique<io::CRawlogWriter>(rawlogFile());
}

std::string CKfSlamSession::rawlogFile(bool final) const
{
  const std::string& dir =
      final && !m_setup.finalOutputDir.empty() ? m_setup.finalOutputDir : m_setup.outputDir;
  return (fs::path(dir) / "kf-slam.rawlog").string();
}

void CKfSlamSession::addFrame(
    const io::TRGBDFrame& frame, const mrpt::obs::CObservationBearingRange& processed)
{
  if (!(processed.sensorLocationOnRobot == m_setup.sensorPose))
    throw std::invalid_argument(
        "kf-slam: observation sensor pose " + processed.sensorLocationOnRobot.asString() +
        " differs from the session's " + m_setup.sensorPose.asString());
  const auto result = m_odometry.process(frame);
  mrpt::obs::CActionRobotMovement3D move;
  move.poseChange = m_increments.next(result);
  m_conditioner.addMotion(move.poseChange.cov);
  const auto observation = m_conditioner.condition(
      processed, frame.camera, mrpt::Clock::toDouble(processed.timestamp), result.pose);
  move.estimationMethod = mrpt::obs::CActionRobotMovement3D::emVisualOdometry;
  move.timestamp = mrpt::Clock::fromDouble(frame.timestamp);
  mrpt::obs::CActionCollection actions;
  actions.insert(move);
  mrpt::obs::CSensoryFrame sf;
  sf.insert(std::make_shared<mrpt::obs::CObservationBearingRange>(observation));
  m_rawlog->write(actions);
  m_rawlog->write(sf);
  logStep(observation, move.poseChange);

  m_odometryRobot.push_back(
      result.pose ? m_increments.robotPose(*result.pose)
                  : (m_odometryRobot.empty() ? mrpt::poses::CPose3D() : m_odometryRobot.back()));
  m_stamps.push_back(mrpt::Clock::toDouble(observation.timestamp));
  if (!observation.sensedData.empty() && !m_firstMeasurementStamp)
    m_firstMeasurementStamp = m_stamps.back();
  for (const auto& m : observation.sensedData)
  {
    ++m_measurements;
    if (m_firstSights.count(m.landmarkID))
      continue;
    const auto inRobot = observation.sensorLocationOnRobot.composePoint(sensorPoint(m));
    m_firstSights[m.landmarkID] = {
        m_stamps.back(),
        m_increments.cameraPose(mrpt::poses::CPose3D()).inverseComposePoint(inRobot)};
  }
}

void CKfSlamSession::logStep(
    const mrpt::obs::CObservationBearingRange& observation,
    const mrpt::poses::CPose3DPDFGaussian& motion)
{
  const double t = mrpt::Clock::toDouble(observation.timestamp);
  m_measurementLog << std::setprecision(17) << std::defaultfloat;
  for (const auto& m : observation.sensedData)
    m_measurementLog << t << ' ' << m.landmarkID << ' ' << std::setprecision(9) << m.range << ' '
                     << m.yaw << ' ' << m.pitch << ' ' << std::sqrt(m.covariance(0, 0)) << ' '
                     << std::sqrt(m.covariance(1, 1)) << ' ' << std::sqrt(m.covariance(2, 2))
                     << '\n'
                     << std::setprecision(17);
  m_motionLog << std::setprecision(17) << t << std::setprecision(9);
  for (int k = 0; k < 6; ++k)
    m_motionLog << ' ' << motion.mean[k];
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c)
      m_motionLog << ' ' << motion.cov(r, c);
  m_motionLog << '\n';
}

nlohmann::json CKfSlamSession::finish(const std::optional<io::TTrajectory>& gt)
{
  m_rawlog->commit();
  const TKfSlamRun run = m_filter.run(rawlogFile());
  const auto ekf = cameraTrajectory(worldRobotPath(run, m_odometryRobot), m_stamps, m_increments);
  const auto odometry = cameraTrajectory(m_odometryRobot, m_stamps, m_increments);
  writeOutputs(ekf, odometry, run);

  nlohmann::json j;
  j["rawlog"] = rawlogFile(true);
  j["kf_slam_ini"] = m_kfSlamIni;
  j["front_end"] = frontend::toString(m_odometry.options().mode);
  j["odometry_covariance"] = m_setup.options.odometry_covariance;
  j["frames"] = m_stamps.size();
  j["measurements"] = m_measurements;
  j["measurements_skipped"] = m_conditioner.skipped();
  j["measurements_gated"] = m_conditioner.gated();
  j["landmarks"] = run.landmarks.size();
  j["first_landmark_frame"] = common::jsonOrNull(run.firstLandmarkStep);
  j["filter_s"] = run.seconds;
  for (const char* k :
       {"ate_rmse", "rpe_trans_rmse", "rpe_rot_rmse_deg", "odometry_ate_rmse",
        "odometry_rpe_trans_rmse", "odometry_rpe_rot_rmse_deg", "landmark_error_m"})
    j[k] = nullptr;
  if (gt)
    j.update(evaluate(*gt, ekf, odometry, run));
  return j;
}

nlohmann::json CKfSlamSession::evaluate(
    const io::TTrajectory& gt, const io::TTrajectory& ekf, const io::TTrajectory& odometry,
    const TKfSlamRun& run)
{
  nlohmann::json j;
  try
  {
    const evaluation::CTrajectoryEvaluator evaluator;
    const auto e = evaluator.evaluate(gt, ekf);
    const auto o = evaluator.evaluate(gt, odometry);
    j["ate_rmse"] = e.ate.rmse;
    j["rpe_trans_rmse"] = e.rpe.trans_rmse;
    j["rpe_rot_rmse_deg"] = e.rpe.rot_rmse_deg;
    j["odometry_ate_rmse"] = o.ate.rmse;
    j["odometry_rpe_trans_rmse"] = o.rpe.trans_rmse;
    j["odometry_rpe_rot_rmse_deg"] = o.rpe.rot_rmse_deg;
  }
  catch (const std::exception& e)
  {
    j["evaluation_error"] = common::firstLine(e.what());
  }
  if (run.firstLandmarkStep)
  {
    const auto reference =
        referenceLandmarks(m_firstSights, gt, m_stamps.at(*run.firstLandmarkStep), m_increments);
    saveKfSlamLandmarks(
        (fs::path(m_setup.outputDir) / "kf-slam.landmarks_gt.txt").string(), reference);
    j["landmark_error_m"] = common::jsonOrNull(meanLandmarkError(run.landmarks, reference));
  }
  return j;
}

void CKfSlamSession::writeOutputs(
    const io::TTrajectory& ekf, const io::TTrajectory& odometry, const TKfSlamRun& run) const
{
  const fs::path dir = fs::path(m_setup.outputDir) / "kf-slam";
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec)
    throw std::runtime_error(dir.string() + ": cannot create folder");
  io::saveTumTrajectory((dir / "trajectory.txt").string(), ekf, "MRPT kf-slam on ROI landmarks");
  io::saveTumTrajectory((dir / "odometry.txt").string(), odometry, "front-end odometry alone");
  // The map in the trajectory's world: the filter's frame is the robot's at
  // its first landmark step.
  std::ostringstream map;
  map << "# id x y z (m, world of trajectory.txt)\n" << std::setprecision(9);
  if (run.firstLandmarkStep)
  {
    const mrpt::poses::CPose3D origin = m_odometryRobot.at(*run.firstLandmarkStep);
    for (const auto& [id, p] : run.landmarks)
    {
      const auto w = origin.composePoint(p);
      map << id << ' ' << w.x << ' ' << w.y << ' ' << w.z << '\n';
    }
  }
  common::writeFileAtomically((dir / "landmarks.txt").string(), map.str());
  common::writeFileAtomically(
      (dir / "measurements.txt").string(),
      "# stamp id range yaw pitch sigma_range sigma_yaw sigma_pitch (m, rad; MRPT sensor frame)\n" +
          m_measurementLog.str());
  common::writeFileAtomically(
      (dir / "motions.txt").string(),
      "# stamp x y z yaw pitch roll (robot motion since the previous frame, m, rad) and its "
      "6x6 covariance, row-major\n" +
          m_motionLog.str());
}
}  // namespace roislam::kfslam
