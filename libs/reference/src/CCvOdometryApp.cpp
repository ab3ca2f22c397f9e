#include "roislam/reference/CCvOdometryApp.h"

#include <mrpt/config/CConfigFileMemory.h>
#include <roislam/common/CStrictIniFile.h>
#include <roislam/common/IniKeyCheck.h>
#include <roislam/common/JsonOrNull.h>
#include <roislam/common/TextFiles.h>
#include <roislam/evaluation/CTrajectoryEvaluator.h>
#include <roislam/io/CFrameSource.h>
#include <roislam/io/TumTrajectory.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>

namespace fs = std::filesystem;

namespace roislam::reference
{
namespace
{
const char* kSection = "CvOdometry";

using TProgress = std::function<void(const std::string&)>;

/** The odometry's trajectory (every frame) and the frame counts and mean
 *  odometry time of the summary. */
struct TOdometryRun
{
  io::TTrajectory estimate;
  CCvOdometryApp::TSummary summary;
};

TOdometryRun runOdometry(
    io::CFrameSource& source, const CCvOdometry::TOptions& options, std::size_t maxFrames,
    const TProgress& progress, const std::string& input)
{
  CCvOdometry odometry(options, source.camera());
  TOdometryRun run;
  auto& s = run.summary;
  double msSum = 0;
  while (!maxFrames || s.frames < maxFrames)
  {
    const auto frame = source.next();
    if (!frame)
      break;
    const auto step = odometry.process(*frame);
    run.estimate.push_back({frame->timestamp, step.pose});
    ++s.frames;
    (step.tracked ? s.trackedFrames : s.failedFrames)++;
    msSum += step.ms;
    if (s.frames % 100 == 0)
      progress("  frame " + std::to_string(s.frames) + "/" + std::to_string(source.size()));
  }
  if (s.frames == 0)
    throw std::runtime_error(input + ": no frames");
  s.msPerFrame = msSum / s.frames;
  return run;
}

/** The error against the ground truth, when the sequence has one; a failed
 *  evaluation is a warning, not an error. */
struct TEvaluation
{
  nlohmann::json json = nlohmann::json(nullptr);
  std::string error;
  std::optional<double> ateRmse, rpeTransRmse, rpeRotRmseDeg;
};

TEvaluation evaluate(
    const io::CFrameSource& source, const io::TTrajectory& estimate, const TProgress& progress)
{
  TEvaluation ev;
  if (const auto gtFile = source.groundTruthFile(); gtFile && fs::exists(*gtFile))
    try
    {
      const auto r =
          evaluation::CTrajectoryEvaluator().evaluate(io::loadTumTrajectory(*gtFile), estimate);
      ev.ateRmse = r.ate.rmse;
      ev.rpeTransRmse = r.rpe.trans_rmse;
      ev.rpeRotRmseDeg = r.rpe.rot_rmse_deg;
      ev.json = evaluation::toJson(r);
    }
    catch (const std::exception& e)
    {
      ev.error = e.what();
      progress("cv-odometry: warning: evaluation failed: " + ev.error);
    }
  return ev;
}

/** What summary.json holds. */
nlohmann::json summaryJson(
    const io::CFrameSource& source, const CCvOdometry::TOptions& options,
    const CCvOdometryApp::TSummary& s, const TEvaluation& ev)
{
  nlohmann::json j;
  j["app"] = "cv-odometry";
  j["sequence"] = source.name();
  j["method"] = options.method;
  j["opencv_class"] = "cv::rgbd::" + CCvOdometry::className(options.method);
  j["camera"] = source.camera().cameraName;
  j["sensor"] = source.sensor().toJson();
  if (const auto clock = source.frameClock())
    j["sensor"]["frame_clock"] = io::toJson(*clock);
  mrpt::config::CConfigFileMemory optionsIni;
  options.saveToConfigFile(optionsIni, kSection);
  j["options"] = optionsIni.getContent();
  j["frames"] = s.frames;
  j["tracked_frames"] = s.trackedFrames;
  j["failed_frames"] = s.failedFrames;
  j["ms_per_frame"] = s.msPerFrame;
  j["wall_s"] = s.wallS;
  j["fps"] = s.fps;
  j["ate_rmse"] = common::jsonOrNull(s.ateRmse);
  j["rpe_trans_rmse"] = common::jsonOrNull(s.rpeTransRmse);
  j["rpe_rot_rmse_deg"] = common::jsonOrNull(s.rpeRotRmseDeg);
  j["evaluation"] = ev.json;
  if (!ev.error.empty())
    j["evaluation_error"] = ev.error;
  j["failed"] = false;
  return j;
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
  const TProgress progress = [&](const std::string& line)
  {
    if (m_args.progress)
      m_args.progress(line);
  };
  progress(
      "cv-odometry: " + source->name() + ", " + std::to_string(source->size()) + " frames, " +
      CCvOdometry::className(m_options.method) + ", camera " + source->camera().cameraName);
  progress("cv-odometry: " + source->sensor().summary());

  TOdometryRun run = runOdometry(*source, m_options, m_args.maxFrames, progress, m_args.input);
  TSummary& s = run.summary;
  s.wallS = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  s.fps = s.frames / s.wallS;

  const TEvaluation ev = evaluate(*source, run.estimate, progress);
  s.ateRmse = ev.ateRmse;
  s.rpeTransRmse = ev.rpeTransRmse;
  s.rpeRotRmseDeg = ev.rpeRotRmseDeg;

  io::saveTumTrajectory(
      (fs::path(m_args.outputDir) / "trajectory.txt").string(), run.estimate,
      "cv-odometry " + source->name() + " cv::rgbd::" + CCvOdometry::className(m_options.method) +
          " frame to frame");
  s.json = summaryJson(*source, m_options, s, ev);
  common::writeFileAtomically(
      (fs::path(m_args.outputDir) / "summary.json").string(), s.json.dump(2) + "\n");
  return s;
}
}  // namespace roislam::reference
