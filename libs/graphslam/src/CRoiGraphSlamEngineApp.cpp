#include <roislam/common/CStrictIniFile.h>
#include <roislam/graphslam/CRoiGraphSlamEngineApp.h>
#include <roislam/graphslam/CRoislamOptionsChecker.h>
#include <roislam/graphslam/CSlamRunner.h>
#include <roislam/graphslam/SensorFacts.h>
#include <roislam/io/TumTrajectory.h>

#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <tuple>

namespace fs = std::filesystem;

namespace roislam::graphslam
{
CRoiGraphSlamEngineApp::CRoiGraphSlamEngineApp(TArguments arguments) : m_args(std::move(arguments))
{
  if (m_args.twoD && m_args.threeD)
    throw std::invalid_argument("--2d and --3d: give one");
  if (m_args.twoD)
    throw std::invalid_argument(
        "--2d: roi-graphslam-engine builds 3-D graphs of RGB-D frames (CNetworkOfPoses3DInf); "
        "for 2-D laser SLAM use MRPT's graphslam-engine");
  const CRoislamOptionsChecker checker;
  const auto& d = m_args.deciders;
  for (const auto& [type, flag, name] :
       {std::tuple<std::string, std::string, std::string>{"node", "-n/--node-reg", d.node},
        {"edge", "-e/--edge-reg", d.edge},
        {"optimizer", "-o/--optimizer", d.optimizer}})
  {
    const std::string why = checker.refusal(type, name);
    if (!why.empty())
      throw std::invalid_argument(flag + " " + name + ": " + why);
  }
  if (m_args.iniFile.empty())
    throw std::invalid_argument("-i/--ini-file is required");
  // Every line checked (file:line errors): MRPT's engine reads the same file
  // leniently afterwards.
  const common::CStrictIniFile cfg(m_args.iniFile);
  // MRPT 2.5.8's CLevMarqGSO joins a thread it never started (abort).
  if (d.optimizer == "CLevMarqGSO" &&
      cfg.read_bool("OptimizerParameters", "optimization_on_second_thread", false))
    throw std::invalid_argument(
        "ini " + m_args.iniFile +
        ": [OptimizerParameters] optimization_on_second_thread: must be false with CLevMarqGSO "
        "(MRPT 2.5.8 aborts on its first optimisation)");
  if (m_args.rawlog.empty())
    throw std::invalid_argument("-r/--rawlog is required");
  // Camera facts (rolling-shutter readout, depth noise) come from the sensor
  // description, as in roi-graphslam; a readout still set in the ini wins.
  m_iniReadout = iniSetsReadout(cfg, m_args.iniFile);
  m_source = io::CFrameSource::open(m_args.rawlog, m_args.camera);
  if (m_args.groundTruth)
    io::loadTumTrajectory(*m_args.groundTruth);  // a bad file fails now, not after the run
}

TSlamSummary CRoiGraphSlamEngineApp::run()
{
  if (!m_source)
    throw std::logic_error("CRoiGraphSlamEngineApp::run: called twice");
  CSlamRunner::TSettings settings;
  settings.app = "roi-graphslam-engine";
  settings.input = m_args.rawlog;
  settings.outputDir = m_args.outputDir;
  settings.overwrite = m_args.overwrite;
  settings.groundTruthFile = m_args.groundTruth;
  settings.snapshot = m_args.snapshot;
  settings.progress = m_args.progress;
  settings.readoutFrom = readoutOrigin(m_iniReadout);
  settings.observer = m_args.observer;
  // As graphslam-engine does: the parameters in use, before the run.
  settings.started = [gt = m_args.groundTruth](const CSlamPipeline& p)
  {
    p.engine().printParams();
    // MRPT 2.5 reads no ground truth for 3-D graphs: the engine has none.
    if (gt)
      std::cout << "Ground truth (TUM, evaluated after the run) = " << *gt << "\n";
  };
  return CSlamRunner(std::move(settings))
      .run(
          std::move(m_source),
          [this](std::unique_ptr<io::CFrameSource> s)
          {
            const io::TSensorChoice sensor = s->sensor();
            return std::make_unique<CSlamPipeline>(
                m_args.deciders, m_args.iniFile, std::move(s),
                [this, &sensor](CSlamContext::TConfig& config)
                {
                  applySensorFacts(
                      config.frontEnd, sensor, m_iniReadout, "roi-graphslam-engine", m_args.iniFile,
                      m_args.progress);
                });
          });
}

std::string CRoiGraphSlamEngineApp::list(const std::string& what)
{
  const CRoislamOptionsChecker checker;
  std::string out;
  if (what == "node" || what == "all")
    out += "Node registration deciders (3-D graphs):\n" + checker.describeRegistrars("node");
  if (what == "edge" || what == "all")
    out += "Edge registration deciders (3-D graphs):\n" + checker.describeRegistrars("edge");
  if (what == "optimizer")
    out += "Optimizers (3-D graphs):\n" + checker.describeOptimizers();
  return out;
}
}  // namespace roislam::graphslam
