#include <mrpt/system/CTicTac.h>
#include <roislam/common/ErrorText.h>
#include <roislam/common/JsonOrNull.h>
#include <roislam/evaluation/CTrajectoryEvaluator.h>
#include <roislam/graphslam/CSlamOutputWriter.h>
#include <roislam/graphslam/CSlamRunner.h>
#include <sys/resource.h>

#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <set>
#include <sstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace roislam::graphslam
{
namespace
{
double peakRssMb()
{
  struct rusage ru
  {
  };
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss / 1024.0;  // KiB on Linux
}

/** What ran on what: the sequence, the engine's deciders, the front end's
 *  configuration and the sensor. */
nlohmann::json runJson(const CSlamPipeline& pipeline, const CSlamRunner::TSettings& settings)
{
  const auto& fe = pipeline.context().config().frontEnd;
  const auto& names = pipeline.deciders().names;
  nlohmann::json j;
  j["sequence"] = pipeline.source().name();
  j["input"] = settings.input;
  j["engine"] = {
      {"node_registration_decider", names.node},
      {"edge_registration_decider", names.edge},
      {"optimizer", names.optimizer}};
  j["mode"] = frontend::toString(fe.mode);
  j["feature"] = features::toString(fe.extractor.feature_type);
  j["max_features"] = fe.extractor.max_features;
  j["strict_roi"] = fe.strict_roi;
  j["sensor"] = pipeline.source().sensor().toJson();
  j["sensor"]["rolling_shutter_ms_used"] = fe.rolling_shutter_ms;
  j["sensor"]["rolling_shutter_from"] = settings.readoutFrom;
  if (const auto clock = pipeline.source().frameClock())
    j["sensor"]["frame_clock"] = io::toJson(*clock);
  return j;
}

/** The map the back end built: keyframes, loop closures, landmarks, the
 *  graph and its optimisations. */
nlohmann::json mapJson(
    const CSlamPipeline& pipeline, const TSlamSummary& s,
    const std::optional<TOptimizationReport>& finalReport)
{
  const CSlamContext& ctx = pipeline.context();
  nlohmann::json j;
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
  j["graph_nodes"] = s.graphNodes;
  j["graph_edges"] = s.graphEdges;
  j["optimizations"] = common::jsonOrNull(pipeline.optimizations());
  j["optimizations_windowed"] = common::jsonOrNull(pipeline.windowedOptimizations());
  j["final_optimization"] = finalReport ? nlohmann::json{{"iterations", finalReport->iterations},
                                                         {"chi2_before", finalReport->chi2Before},
                                                         {"chi2_after", finalReport->chi2After},
                                                         {"variance_factor", ctx.varianceFactor()},
                                                         {"loop_variance_factor", ctx.loopVarianceFactor()},
                                                         {"seconds", finalReport->seconds}}
                                        : nlohmann::json(nullptr);
  return j;
}

/** How the front end tracked the frames and what it cost. */
nlohmann::json trackingJson(const CSlamPipeline& pipeline, const TSlamSummary& s)
{
  const auto& st = pipeline.context().odometry().stats();
  nlohmann::json j;
  j["tracked_frames"] = s.trackedFrames;
  j["fallback_frames"] = s.fallbackFrames;
  j["lost_frames"] = s.lostFrames;
  j["tracking"] = {
      {"initial", st.initial},
      {"features", st.features},
      {"roi", st.roiFeatures},
      {"flow", st.flow},
      {"full_image_fallback", st.fullImageFallback},
      {"depth_icp", st.depthIcp},
      {"constant_velocity", st.constantVelocity},
      {"lost", st.lost},
      {"no_roi", st.noRoi},
      {"icp_refined", st.icpRefined},
      {"icp_overruled_features", st.icpOverruledFeatures},
      {"icp_replaced_features", st.icpReplacedFeatures},
      {"feature_scale", common::jsonOrNull(st.featureScale)},
      {"icp_joint_scale", common::jsonOrNull(st.icpJointScale)},
      {"bridged", st.bridged},
      {"bridged_constraints", st.bridgedConstraints}};
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
  // All front-end work per frame (frames.csv frontend_ms: decoding excluded),
  // the cost the ROI versions are compared by.
  double frontMs = 0;
  for (const auto& r : pipeline.records())
    frontMs += r.result.times.total_ms;
  j["frontend_ms_per_frame"] = s.frames > 0 ? frontMs / s.frames : 0.0;
  return j;
}
}  // namespace

std::string TSlamSummary::resultLine() const
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

CSlamRunner::CSlamRunner(TSettings settings) : m_settings(std::move(settings)) {}

void CSlamRunner::progress(const std::string& line) const
{
  if (m_settings.progress)
    m_settings.progress(line);
}

bool CSlamRunner::runFrames(CSlamPipeline& pipeline, std::size_t total) const
{
  const auto& records = pipeline.records();
  const std::size_t maxFrames = m_settings.maxFrames;
  const auto stop = [this] { return m_settings.observer && m_settings.observer->stopRequested(); };
  while ((!maxFrames || records.size() < maxFrames) && !stop() && pipeline.step())
    if (records.size() % 50 == 0)
      progress(
          "  frame " + std::to_string(records.size()) + "/" + std::to_string(total) +
          ", keyframes " + std::to_string(pipeline.context().odometry().keyframes().size()) +
          ", loops " + std::to_string(pipeline.context().loopClosures().size()));
  if (records.empty())
    throw std::runtime_error(
        m_settings.input + (stop() ? ": stopped before the first frame" : ": no frames"));
  const bool stopped = stop() && records.size() < total;
  if (stopped)
    progress(
        m_settings.app + ": stopped after frame " + std::to_string(records.size()) +
        ", writing the outputs");
  return stopped;
}

CSlamRunner::TEvaluation CSlamRunner::evaluate(
    const CSlamPipeline& pipeline, const io::TTrajectory& estimate) const
{
  TEvaluation ev;
  const auto& gtFile = m_settings.groundTruthFile;
  if (!gtFile)
    return ev;
  try
  {
    ev.groundTruth = io::loadTumTrajectory(*gtFile);
    ev.result = evaluation::CTrajectoryEvaluator().evaluate(ev.groundTruth, estimate);
    if (const std::string w = evaluation::mirrorWarning(ev.result->ate); !w.empty())
      progress(m_settings.app + ": " + w);
    // The causal front-end estimate (poses as tracked, before later
    // optimisations), to show what the back end adds.
    io::TTrajectory odometryOnly;
    for (const auto& r : pipeline.records())
      if (r.result.pose)
        odometryOnly.push_back({r.result.timestamp, *r.result.pose});
    ev.odometryAte =
        evaluation::CTrajectoryEvaluator().evaluate(ev.groundTruth, odometryOnly).ate.rmse;
    ev.edgeChi2 = edgeChi2(pipeline, ev.groundTruth);
  }
  catch (const std::exception& e)
  {
    ev.result.reset();
    ev.error = common::firstLine(e.what());
    progress(m_settings.app + ": warning: evaluation failed: " + ev.error);
  }
  return ev;
}

std::optional<evaluation::TEdgeChi2> CSlamRunner::edgeChi2(
    const CSlamPipeline& pipeline, const io::TTrajectory& groundTruth)
{
  const auto& keyframes = pipeline.context().odometry().keyframes();
  std::set<std::pair<std::size_t, std::size_t>> loops;
  for (const auto& lc : pipeline.context().loopClosures())
    loops.insert({lc.fromKeyframe, lc.toKeyframe});
  // Every frame's stamp: their jitter is measured over all of them.
  std::vector<double> stamps;
  for (const auto& r : pipeline.records())
    stamps.push_back(r.result.timestamp);
  std::sort(stamps.begin(), stamps.end());
  return evaluation::edgeChi2(
      pipeline.graph(),
      [&keyframes](mrpt::graphs::TNodeID id)
      { return id < keyframes.size() ? keyframes[id].timestamp : -1.0; },
      groundTruth, 0.02,
      [&loops](mrpt::graphs::TNodeID from, mrpt::graphs::TNodeID to) -> std::string
      {
        if (loops.count({from, to}))
          return "loop";
        return to == from + 1 ? "odometry" : "keyframe";
      },
      stamps);
}

TSlamSummary CSlamRunner::summarize(
    const CSlamPipeline& pipeline, const io::TTrajectory& estimate, double wallS,
    const TEvaluation& ev) const
{
  const auto& odo = pipeline.context().odometry();
  const auto& st = odo.stats();
  TSlamSummary s;
  s.frames = pipeline.records().size();
  s.keyframes = odo.keyframes().size();
  s.loopClosures = pipeline.context().loopClosures().size();
  s.graphNodes = pipeline.graph().nodes.size();
  s.graphEdges = pipeline.graph().edges.size();
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

nlohmann::json CSlamRunner::summaryJson(
    const CSlamPipeline& pipeline, const TSlamSummary& s,
    const std::optional<TOptimizationReport>& finalReport, const TEvaluation& ev) const
{
  // The parts have disjoint keys (and nlohmann::json sorts them), so merging
  // gives the object the single function built.
  nlohmann::json j = runJson(pipeline, m_settings);
  j.update(mapJson(pipeline, s, finalReport));
  j.update(trackingJson(pipeline, s));
  // The outcome: timing, failure, the error against the ground truth.
  j["failed"] = s.failed;
  j["stopped_by_user"] = s.stoppedByUser;
  j["wall_s"] = s.wallS;
  j["fps"] = s.fps;
  j["map_s"] = s.mapS;
  j["snapshot_s"] = m_settings.snapshot ? nlohmann::json(s.snapshotS) : nlohmann::json(nullptr);
  j["peak_rss_mb"] = s.peakRssMb;
  j["ate_rmse"] = common::jsonOrNull(s.ateRmse);
  j["rpe_trans_rmse"] = common::jsonOrNull(s.rpeTransRmse);
  j["rpe_rot_rmse_deg"] = common::jsonOrNull(s.rpeRotRmseDeg);
  j["frontend_ate_rmse"] = common::jsonOrNull(ev.odometryAte);
  j["edge_chi2"] = ev.edgeChi2 ? evaluation::toJson(*ev.edgeChi2) : nlohmann::json(nullptr);
  j["evaluation"] = ev.result ? evaluation::toJson(*ev.result) : nlohmann::json(nullptr);
  if (!ev.error.empty())
    j["evaluation_error"] = ev.error;
  return j;
}

void CSlamRunner::writeOutputs(
    CSlamOutputWriter& writer, const CSlamPipeline& pipeline, const io::TTrajectory& estimate,
    const std::optional<TOptimizationReport>& finalReport, const TEvaluation& ev,
    TSlamSummary& s) const
{
  writer.writeTrajectory(
      estimate, m_settings.app + " " + pipeline.source().name() + " mode " +
                    frontend::toString(pipeline.context().config().frontEnd.mode));
  writer.writeGraph(pipeline.graph());
  writer.writeFramesCsv(pipeline.records());
  writer.writeReport(pipeline.report());

  const CSlamOutputWriter::TRun run{
      pipeline.records(), pipeline.context(), pipeline.graph(),
      [&pipeline](std::size_t id) { return pipeline.keyframePose(id); }};
  const CSlamOutputWriter::TReference reference{
      pipeline.source().name(), estimate, ev.groundTruth, ev.result ? &*ev.result : nullptr,
      pipeline.source().accelerometerFile()};
  const auto pictures = writer.writePictures(run, reference, m_settings.snapshot);
  for (const auto& w : pictures.warnings())
    progress(m_settings.app + ": warning: " + w);
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
  writer.writeSummary(j);  // renames the folder into place
}

TSlamSummary CSlamRunner::run(
    std::unique_ptr<io::CFrameSource> source, const TMakePipeline& make) const
{
  // Before the run: a folder we may not write fails now, not after the work.
  CSlamOutputWriter writer(m_settings.outputDir, m_settings.overwrite);
  const std::string name = source->name();
  const std::size_t total = source->size();

  mrpt::system::CTicTac wall;
  const std::unique_ptr<CSlamPipeline> pipeline = make(std::move(source));
  const auto& fe = pipeline->context().config().frontEnd;
  progress(
      m_settings.app + ": " + name + ", " + std::to_string(total) + " frames, mode " +
      frontend::toString(fe.mode) + ", " + features::toString(fe.extractor.feature_type));
  if (m_settings.started)
    m_settings.started(*pipeline);
  pipeline->setObserver(m_settings.observer);
  if (m_settings.observer)
    m_settings.observer->onOutputFolder(writer.folder());
  const bool stopped = runFrames(*pipeline, total);
  const auto finalReport = pipeline->finish();
  const io::TTrajectory estimate = pipeline->trajectory();
  const double wallS = wall.Tac();

  const TEvaluation ev = evaluate(*pipeline, estimate);
  TSlamSummary s = summarize(*pipeline, estimate, wallS, ev);
  s.stoppedByUser = stopped;
  if (!ev.error.empty())
    s.incomplete.push_back("evaluation failed: " + ev.error);
  writeOutputs(writer, *pipeline, estimate, finalReport, ev, s);
  if (m_settings.observer)
    m_settings.observer->onOutputFolder(writer.folder());
  return s;
}
}  // namespace roislam::graphslam
