#include <mrpt/system/CTicTac.h>
#include <roislam/common/CStrictIniFile.h>
#include <roislam/evaluation/CTrajectoryEvaluator.h>
#include <roislam/frontend/PoseUncertainty.h>
#include <roislam/graphslam/CKeyframeERD.h>
#include <roislam/graphslam/CKeyframeNRD.h>
#include <roislam/graphslam/CRoiGraphSlamApp.h>
#include <roislam/graphslam/CRoislamOptionsChecker.h>
#include <roislam/graphslam/CSlamOutputWriter.h>
#include <roislam/graphslam/CSlamPipeline.h>
#include <roislam/io/CFrameSource.h>
#include <roislam/io/TumTrajectory.h>
#include <sys/resource.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <future>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace roislam::graphslam
{
namespace
{
std::string firstLine(const std::string& s)
{
  return s.substr(0, s.find('\n'));
}

double peakRssMb()
{
  struct rusage ru
  {
  };
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss / 1024.0;  // KiB on Linux
}

nlohmann::json optionalJson(const std::optional<double>& v)
{
  return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
}
}  // namespace

std::string CRoiGraphSlamApp::TSummary::resultLine() const
{
  std::ostringstream ss;
  ss << std::fixed;
  if (ateRmse)
    ss << "ATE RMSE " << std::setprecision(4) << *ateRmse << " m, ";
  else
    ss << "ATE n/a, ";
  if (rpeTransRmse && rpeRotRmseDeg)
    ss << "RPE " << std::setprecision(4) << *rpeTransRmse << " m / " << std::setprecision(2)
       << *rpeRotRmseDeg << " deg, ";
  ss << frames << " frames, " << keyframes << " keyframes, " << loopClosures << " loop closures, "
     << std::setprecision(1) << fps << " fps";
  if (failed)
    ss << ", FAILED (" << lostFrames << " frames lost)";
  return ss.str();
}

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

void CRoiGraphSlamApp::progress(const std::string& line) const
{
  if (m_args.progress)
    m_args.progress(line);
}

void CRoiGraphSlamApp::runFrames(CSlamPipeline& pipeline, std::size_t total) const
{
  const auto& records = pipeline.records();
  while ((!m_args.maxFrames || records.size() < m_args.maxFrames) && pipeline.step())
    if (records.size() % 50 == 0)
      progress(
          "  frame " + std::to_string(records.size()) + "/" + std::to_string(total) +
          ", keyframes " + std::to_string(pipeline.context().odometry().keyframes().size()) +
          ", loops " + std::to_string(pipeline.context().loopClosures().size()));
  if (records.empty())
    throw std::runtime_error(m_args.input + ": no frames");
}

CRoiGraphSlamApp::TEvaluation CRoiGraphSlamApp::evaluate(
    const CSlamPipeline& pipeline, const io::TTrajectory& estimate) const
{
  TEvaluation ev;
  const auto gtFile = pipeline.source().groundTruthFile();
  if (!gtFile || !fs::exists(*gtFile))
    return ev;
  try
  {
    ev.groundTruth = io::loadTumTrajectory(*gtFile);
    ev.result = evaluation::CTrajectoryEvaluator().evaluate(ev.groundTruth, estimate);
    // The causal front-end estimate (poses as tracked, before later
    // optimisations), to show what the back end adds.
    io::TTrajectory odometryOnly;
    for (const auto& r : pipeline.records())
      if (r.result.pose)
        odometryOnly.push_back({r.result.timestamp, *r.result.pose});
    ev.odometryAte =
        evaluation::CTrajectoryEvaluator().evaluate(ev.groundTruth, odometryOnly).ate.rmse;
  }
  catch (const std::exception& e)
  {
    ev.result.reset();
    ev.error = firstLine(e.what());
    progress("roi-graphslam: warning: evaluation failed: " + ev.error);
  }
  return ev;
}

CRoiGraphSlamApp::TSummary CRoiGraphSlamApp::summarize(
    const CSlamPipeline& pipeline, const io::TTrajectory& estimate, double wallS,
    const TEvaluation& ev) const
{
  const auto& odo = pipeline.context().odometry();
  const auto& st = odo.stats();
  TSummary s;
  s.frames = pipeline.records().size();
  s.keyframes = odo.keyframes().size();
  s.loopClosures = pipeline.context().loopClosures().size();
  s.trackedFrames = estimate.size();
  s.lostFrames = st.lost;
  s.fallbackFrames = st.fullImageFallback + st.depthIcp + st.constantVelocity;
  s.wallS = wallS;
  s.fps = wallS > 0 ? s.frames / wallS : 0;
  s.failed = s.lostFrames > 0 || estimate.empty();
  if (ev.result)
  {
    s.ateRmse = ev.result->ate.rmse;
    s.rpeTransRmse = ev.result->rpe.trans_rmse;
    s.rpeRotRmseDeg = ev.result->rpe.rot_rmse_deg;
  }
  return s;
}

nlohmann::json CRoiGraphSlamApp::summaryJson(
    const CSlamPipeline& pipeline, const TSummary& s, const TOptimizationReport& finalReport,
    const TEvaluation& ev) const
{
  const CSlamContext& ctx = pipeline.context();
  const auto& st = ctx.odometry().stats();
  const auto& fe = m_config.frontEnd;
  nlohmann::json j;
  j["sequence"] = pipeline.source().name();
  j["input"] = m_args.input;
  j["mode"] = frontend::toString(fe.mode);
  j["feature"] = features::toString(fe.extractor.feature_type);
  j["max_features"] = fe.extractor.max_features;
  j["strict_roi"] = fe.strict_roi;
  j["frames"] = s.frames;
  j["skipped_frames"] = pipeline.source().skippedFrames();
  j["keyframes"] = s.keyframes;
  j["loop_closures"] = s.loopClosures;
  std::size_t lmLoops = 0;
  for (const auto& lc : ctx.loopClosures())
    lmLoops += lc.source == ELoopSource::Landmark;
  j["loop_closures_landmark"] = lmLoops;
  j["loop_closures_proximity"] = s.loopClosures - lmLoops;
  j["loop_closures_rejected"] = ctx.rejectedLoopClosures();
  j["landmarks"] = ctx.database().size();
  j["graph_nodes"] = pipeline.graph().nodes.size();
  j["graph_edges"] = pipeline.graph().edges.size();
  j["optimizations"] = pipeline.optimizations();
  j["optimizations_windowed"] = pipeline.windowedOptimizations();
  j["final_optimization"] = {
      {"iterations", finalReport.iterations},
      {"chi2_before", finalReport.chi2Before},
      {"chi2_after", finalReport.chi2After},
      {"seconds", finalReport.seconds}};
  j["tracked_frames"] = s.trackedFrames;
  j["fallback_frames"] = s.fallbackFrames;
  j["lost_frames"] = s.lostFrames;
  j["tracking"] = {
      {"initial", st.initial},
      {"features", st.features},
      {"roi", st.roiFeatures},
      {"full_image_fallback", st.fullImageFallback},
      {"depth_icp", st.depthIcp},
      {"constant_velocity", st.constantVelocity},
      {"lost", st.lost},
      {"no_roi", st.noRoi},
      {"icp_refined", st.icpRefined}};
  // What stage 2 described: ROI-only frames describe their tracking region
  // alone; the others were extended once, for the reason given.
  nlohmann::json ext = nlohmann::json::object();
  for (const auto& [reason, n] : st.extensions)
    if (reason != frontend::EExtension::None)
      ext[frontend::toString(reason)] = n;
  const auto roiOnly = st.extensions.find(frontend::EExtension::None);
  j["described_pixel_fraction"] = st.frames > 0 ? st.describedFractionSum / st.frames : 0.0;
  j["roi_only_frames"] = roiOnly == st.extensions.end() ? 0 : roiOnly->second;
  j["extended_frames"] = ext;
  j["failed"] = s.failed;
  j["wall_s"] = s.wallS;
  j["fps"] = s.fps;
  j["map_s"] = s.mapS;
  j["snapshot_s"] = m_args.snapshot ? nlohmann::json(s.snapshotS) : nlohmann::json(nullptr);
  j["peak_rss_mb"] = s.peakRssMb;
  j["ate_rmse"] = optionalJson(s.ateRmse);
  j["rpe_trans_rmse"] = optionalJson(s.rpeTransRmse);
  j["rpe_rot_rmse_deg"] = optionalJson(s.rpeRotRmseDeg);
  j["frontend_ate_rmse"] = optionalJson(ev.odometryAte);
  j["evaluation"] = ev.result ? evaluation::toJson(*ev.result) : nlohmann::json(nullptr);
  if (!ev.error.empty())
    j["evaluation_error"] = ev.error;
  return j;
}

CRoiGraphSlamApp::TSummary CRoiGraphSlamApp::run()
{
  auto source = io::CFrameSource::open(m_args.input, m_args.camera);
  // Before the run: a folder we may not write fails now, not after the work.
  CSlamOutputWriter writer(m_args.outputDir, m_args.overwrite);
  progress(
      "roi-graphslam: " + source->name() + ", " + std::to_string(source->size()) +
      " frames, mode " + frontend::toString(m_config.frontEnd.mode) + ", " +
      features::toString(m_config.frontEnd.extractor.feature_type));

  mrpt::system::CTicTac wall;
  const std::size_t total = source->size();
  CSlamPipeline pipeline(m_config, std::move(source));
  runFrames(pipeline, total);
  const auto finalReport = pipeline.finish();
  const io::TTrajectory estimate = pipeline.trajectory();
  const double wallS = wall.Tac();

  const TEvaluation ev = evaluate(pipeline, estimate);
  TSummary s = summarize(pipeline, estimate, wallS, ev);
  if (!ev.error.empty())
    s.incomplete.push_back("evaluation failed: " + ev.error);

  writer.writeTrajectory(
      estimate, "roi-graphslam " + pipeline.source().name() + " mode " +
                    frontend::toString(m_config.frontEnd.mode));
  writer.writeGraph(pipeline.graph());
  writer.writeFramesCsv(pipeline.records());

  const CSlamOutputWriter::TRun run{
      pipeline.records(), pipeline.context(), pipeline.graph(),
      [&pipeline](std::size_t id) { return pipeline.keyframePose(id); }};
  const CSlamOutputWriter::TReference reference{
      pipeline.source().name(), estimate, ev.groundTruth, ev.result ? &*ev.result : nullptr,
      pipeline.source().accelerometerFile()};
  const auto pictures = writer.writePictures(run, reference, m_args.snapshot);
  for (const auto& w : pictures.warnings())
    progress("roi-graphslam: warning: " + w);
  // A missing snapshot or plot makes the output partial (exit 3); a picture
  // not levelled by the accelerometer is only a warning.
  if (!pictures.snapshotError.empty())
    s.incomplete.push_back("no snapshot: " + pictures.snapshotError);
  if (!pictures.plotError.empty())
    s.incomplete.push_back("no error plots: " + pictures.plotError);
  s.mapS = pictures.mapS;
  s.snapshotS = pictures.snapshotS;
  s.peakRssMb = peakRssMb();

  nlohmann::json j = summaryJson(pipeline, s, finalReport, ev);
  pictures.addToSummary(j);
  j["partial"] = !s.incomplete.empty();
  j["incomplete"] = s.incomplete;
  writer.writeSummary(j);
  return s;
}
}  // namespace roislam::graphslam
