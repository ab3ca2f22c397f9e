#include <mrpt/config/CConfigFile.h>
#include <mrpt/core/format.h>
#include <roislam/common/CStrictIniFile.h>
#include <roislam/graphslam/CRoiGraphSlamApp.h>
#include <roislam/graphslam/CRoislamOptionsChecker.h>
#include <roislam/graphslam/CSlamRunner.h>
#include <roislam/graphslam/SensorFacts.h>
#include <roislam/io/CFrameSource.h>

#include <filesystem>
#include <stdexcept>

namespace fs = std::filesystem;

namespace roislam::graphslam
{
std::string CRoiGraphSlamApp::listRegistrars(const std::string& type)
{
  return CRoislamOptionsChecker().describeRegistrars(type);
}

CRoiGraphSlamApp::CRoiGraphSlamApp(TArguments arguments) : m_args(std::move(arguments))
{
  if (!m_args.iniFile.empty())
  {
    const common::CStrictIniFile cfg(m_args.iniFile);
    m_config = CSlamContext::loadConfig(cfg, m_args.iniFile);
    m_iniReadout = iniSetsReadout(cfg, m_args.iniFile);
  }
  auto& fe = m_config.frontEnd;
  if (m_args.mode)
    fe.mode = frontend::frontEndModeFromString(*m_args.mode);
  if (m_args.feature)
    fe.extractor.feature_type = features::featureTypeFromString(*m_args.feature);
  if (m_args.maxFeatures)
  {
    if (*m_args.maxFeatures < 0)
      throw std::invalid_argument("--max-features: must be >= 0");
    fe.extractor.max_features = *m_args.maxFeatures;
  }
  if (m_args.strictRoi)
    fe.strict_roi = *m_args.strictRoi;
  // roi_small / roi_big select the detector preset (as the front end does
  // when loading [FrontEnd] mode).
  if (fe.mode == frontend::EFrontEndMode::RoiSmall)
    fe.roi.setPreset("small");
  if (fe.mode == frontend::EFrontEndMode::RoiBig)
    fe.roi.setPreset("big");
  fe.validate();
  m_config.backEnd.validate();
}

void CRoiGraphSlamApp::applySensor(const io::CFrameSource& source)
{
  applySensorFacts(
      m_config.frontEnd, source.sensor(), m_iniReadout, "roi-graphslam", m_args.iniFile,
      m_args.progress);
}

CRoiGraphSlamApp::TSummary CRoiGraphSlamApp::run()
{
  auto source = io::CFrameSource::open(m_args.input, m_args.camera);
  CSlamRunner::TSettings settings;
  settings.app = "roi-graphslam";
  settings.input = m_args.input;
  settings.outputDir = m_args.outputDir;
  settings.overwrite = m_args.overwrite;
  const auto gt = source->groundTruthFile();
  if (gt && fs::exists(*gt))
    settings.groundTruthFile = gt;
  settings.snapshot = m_args.snapshot;
  settings.maxFrames = m_args.maxFrames;
  settings.progress = m_args.progress;
  settings.observer = m_args.observer;
  settings.readoutFrom = readoutOrigin(m_iniReadout);
  // The engine's own keys ([GeneralConfiguration] ...) come from the same
  // ini; our deciders take m_config as it is.
  return CSlamRunner(std::move(settings))
      .run(
          std::move(source),
          [this](std::unique_ptr<io::CFrameSource> s)
          {
            // Called once the runner has checked the output folder: an
            // unwritable one stays the run's only line.
            applySensor(*s);
            return std::make_unique<CSlamPipeline>(m_config, std::move(s), m_args.iniFile);
          });
}
}  // namespace roislam::graphslam
