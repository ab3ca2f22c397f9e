#include "roislam/reference/CCvOdometryApp.h"

#include <mrpt/config/CConfigFileMemory.h>
#include <roislam/common/CStrictIniFile.h>
#include <roislam/common/IniKeyCheck.h>
#include <roislam/common/TextFiles.h>
#include <roislam/evaluation/CTrajectoryEvaluator.h>
#include <roislam/io/CFrameSource.h>
#include <roislam/io/TumTrajectory.h>

#include <chrono>
#include <filesystem>
#include <stdexcept>

namespace fs = std::filesystem;

namespace roislam::reference
{
namespace
{
const char* kSection = "CvOdometry";

nlohmann::json optionalJson(const std::optional<double>& v)
{
  return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
}
}  // namespace

CCvOdometryApp::CCvOdometryApp(const TArguments& args) : m_args(args)
{
  if (m_args.input.empty() || m_args.outputDir.empty())
    throw std::invalid_argument("--input and --output-dir are required");
  if (!m_args.iniFile.empty())
  {
    if (!fs::is_regular_file(m_args.iniFile))
      throw std::runtime_error(m_args.iniFile + ": ini file not found");
    const common::CStrictIniFile cfg(m_args.iniFile);
    common::checkIniKeys(cfg, kSection, common::knownIniKeys(m_options, kSection), m_args.iniFile);
    try
    {
      m_options.loadFromConfigFile(cfg, kSection);
    }
    catch (const std::invalid_argument& e)
    {
      throw std::invalid_argument(m_args.iniFile + ": " + e.what());
    }
  }
  if (!m_args.method.empty())
    m_options.method = m_args.method;
  m_options.validate(m_args.method.empty() ? kSection : "--method");
}

CCvOdometryApp::TSummary CCvOdometryApp::run() const
{
  const auto t0 = std::chrono::steady_clock::now();
  auto source = io::CFrameSource::open(m_args.input, m_args.camera);
  std::error_code ec;
  fs::create_directories(m_args.outputDir, ec);
  if (!fs::is_directory(m_args.outputDir))
    throw std::runtime_error("output dir " + m_args.outputDir + ": cannot create");
  const auto progress = [&](const std::string& line)
  {
    if (m_args.progress)
      m_args.progress(line);
  };
  progress(
      "cv-odometry: " + source->name() + ", " + std::to_string(source->size()) + " frames, " +
      CCvOdometry::className(m_options.method) + ", camera " + source->camera().cameraName);
  progress("cv-odometry: " + source->sensor().summary());

  CCvOdometry odometry(m_options, source->camera());
  io::TTrajectory estimate;
  TSummary s;
  double msSum = 0;
  while (!m_args.maxFrames || s.frames < m_args.maxFrames)
  {
    const auto frame = source->next();
    if (!frame)
      break;
    const auto step = odometry.process(*frame);
    estimate.push_back({frame->timestamp, step.pose});
    ++s.frames;
    (step.tracked ? s.trackedFrames : s.failedFrames)++;
    msSum += step.ms;
    if (s.frames % 100 == 0)
      progress("  frame " + std::to_string(s.frames) + "/" + std::to_string(source->size()));
  }
  if (s.frames == 0)
    throw std::runtime_error(m_args.input + ": no frames");
  s.msPerFrame = msSum / s.frames;
  s.wallS = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  s.fps = s.frames / s.wallS;

  nlohmann::json evaluation(nullptr);
  std::string evaluationError;
  if (const auto gtFile = source->groundTruthFile(); gtFile && fs::exists(*gtFile))
    try
    {
      const auto r =
          evaluation::CTrajectoryEvaluator().evaluate(io::loadTumTrajectory(*gtFile), estimate);
      s.ateRmse = r.ate.rmse;
      s.rpeTransRmse = r.rpe.trans_rmse;
      s.rpeRotRmseDeg = r.rpe.rot_rmse_deg;
      evaluation = evaluation::toJson(r);
    }
    catch (const std::exception& e)
    {
      evaluationError = e.what();
      progress("cv-odometry: warning: evaluation failed: " + evaluationError);
    }

  const std::string opencvClass = CCvOdometry::className(m_options.method);
  io::saveTumTrajectory(
      (fs::path(m_args.outputDir) / "trajectory.txt").string(), estimate,
      "cv-odometry " + source->name() + " cv::rgbd::" + opencvClass + " frame to frame");
  auto& j = s.json;
  j["app"] = "cv-odometry";
  j["sequence"] = source->name();
  j["method"] = m_options.method;
  j["opencv_class"] = "cv::rgbd::" + opencvClass;
  j["camera"] = source->camera().cameraName;
  j["sensor"] = source->sensor().toJson();
  mrpt::config::CConfigFileMemory optionsIni;
  m_options.saveToConfigFile(optionsIni, kSection);
  j["options"] = optionsIni.getContent();
  j["frames"] = s.frames;
  j["tracked_frames"] = s.trackedFrames;
  j["failed_frames"] = s.failedFrames;
  j["ms_per_frame"] = s.msPerFrame;
  j["wall_s"] = s.wallS;
  j["fps"] = s.fps;
  j["ate_rmse"] = optionalJson(s.ateRmse);
  j["rpe_trans_rmse"] = optionalJson(s.rpeTransRmse);
  j["rpe_rot_rmse_deg"] = optionalJson(s.rpeRotRmseDeg);
  j["evaluation"] = evaluation;
  if (!evaluationError.empty())
    j["evaluation_error"] = evaluationError;
  j["failed"] = false;
  common::writeFileAtomically(
      (fs::path(m_args.outputDir) / "summary.json").string(), j.dump(2) + "\n");
  return s;
}
}  // namespace roislam::reference
