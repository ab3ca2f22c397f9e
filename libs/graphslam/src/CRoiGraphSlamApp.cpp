#include <mrpt/config/CConfigFile.h>
#include <mrpt/system/CTicTac.h>
#include <octomap/OcTree.h>
#include <roislam/evaluation/CTrajectoryEvaluator.h>
#include <roislam/frontend/PoseUncertainty.h>
#include <roislam/graphslam/CKeyframeERD.h>
#include <roislam/graphslam/CKeyframeNRD.h>
#include <roislam/graphslam/CRoiGraphSlamApp.h>
#include <roislam/graphslam/CRoislamOptionsChecker.h>
#include <roislam/graphslam/CSlamPipeline.h>
#include <roislam/io/CFrameSource.h>
#include <roislam/io/TumTrajectory.h>
#include <roislam/viz/CSlamSceneBuilder.h>
#include <roislam/viz/CSnapshotRenderer.h>
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

/** Writes text through `file`.tmp renamed on success. */
void writeTextFile(const std::string& file, const std::string& text)
{
  const std::string tmp = file + ".tmp";
  {
    std::ofstream out(tmp);
    out << text;
    out.flush();
    if (!out)
      throw std::runtime_error(file + ": cannot write");
  }
  if (std::rename(tmp.c_str(), file.c_str()) != 0)
  {
    std::remove(tmp.c_str());
    throw std::runtime_error(file + ": cannot rename from " + tmp);
  }
}

void renameOrThrow(const std::string& tmp, const std::string& file)
{
  if (std::rename(tmp.c_str(), file.c_str()) != 0)
  {
    std::remove(tmp.c_str());
    throw std::runtime_error(file + ": cannot rename from " + tmp);
  }
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

void checkWritableDir(const std::string& dir)
{
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    throw std::runtime_error("output dir " + dir + ": cannot create");
  const std::string probe = dir + "/.roi-graphslam-write-test";
  std::ofstream out(probe);
  if (!out)
    throw std::runtime_error("output dir " + dir + ": not writable");
  out.close();
  std::remove(probe.c_str());
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
    if (!fs::is_regular_file(m_args.iniFile))
      throw std::runtime_error("ini " + m_args.iniFile + ": cannot open");
    mrpt::config::CConfigFile cfg(m_args.iniFile);
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

CRoiGraphSlamApp::TSummary CRoiGraphSlamApp::run()
{
  auto progress = [&](const std::string& s)
  {
    if (m_args.progress)
      m_args.progress(s);
  };
  auto source = io::CFrameSource::open(m_args.input, m_args.camera);
  checkWritableDir(m_args.outputDir);
  const std::string out = m_args.outputDir + "/";
  progress(
      "roi-graphslam: " + source->name() + ", " + std::to_string(source->size()) +
      " frames, mode " + frontend::toString(m_config.frontEnd.mode) + ", " +
      features::toString(m_config.frontEnd.extractor.feature_type));

  mrpt::system::CTicTac wall;
  const std::size_t total = source->size();
  CSlamPipeline pipeline(m_config, std::move(source));
  const auto& records = pipeline.records();
  while ((!m_args.maxFrames || records.size() < m_args.maxFrames) && pipeline.step())
    if (records.size() % 50 == 0)
      progress(
          "  frame " + std::to_string(records.size()) + "/" + std::to_string(total) +
          ", keyframes " + std::to_string(pipeline.context().odometry().keyframes().size()) +
          ", loops " + std::to_string(pipeline.context().loopClosures().size()));
  if (records.empty())
    throw std::runtime_error(m_args.input + ": no frames");
  const auto finalReport = pipeline.finish();
  const std::size_t optimizations = pipeline.optimizations();
  const std::size_t windowedOptimizations = pipeline.windowedOptimizations();
  const CSlamContext* ctx = &pipeline.context();
  const TGraph& graph = pipeline.graph();
  const io::CFrameSource* src = &pipeline.source();

  const auto& odo = ctx->odometry();
  const io::TTrajectory estimate = pipeline.trajectory();
  io::TTrajectory odometryOnly;
  for (const auto& r : records)
    if (r.result.pose)
      odometryOnly.push_back({r.result.timestamp, *r.result.pose});
  const double wallS = wall.Tac();

  TSummary s;
  s.frames = records.size();
  s.keyframes = odo.keyframes().size();
  s.loopClosures = ctx->loopClosures().size();
  const auto& st = odo.stats();
  s.trackedFrames = estimate.size();
  s.lostFrames = st.lost;
  s.fallbackFrames = st.fullImageFallback + st.depthIcp + st.constantVelocity;
  s.wallS = wallS;
  s.fps = wallS > 0 ? s.frames / wallS : 0;
  s.failed = s.lostFrames > 0 || estimate.empty();

  // Evaluation against ground truth.
  std::optional<evaluation::TEvaluationResult> eval;
  std::optional<double> odometryAte;
  std::string evalError;
  if (const auto gtFile = src->groundTruthFile(); gtFile && fs::exists(*gtFile))
  {
    try
    {
      const auto gt = io::loadTumTrajectory(*gtFile);
      eval = evaluation::CTrajectoryEvaluator().evaluate(gt, estimate);
      s.ateRmse = eval->ate.rmse;
      s.rpeTransRmse = eval->rpe.trans_rmse;
      s.rpeRotRmseDeg = eval->rpe.rot_rmse_deg;
      // The causal front-end estimate (poses as tracked, before later
      // optimisations), to show what the back end adds.
      odometryAte = evaluation::CTrajectoryEvaluator().evaluate(gt, odometryOnly).ate.rmse;
    }
    catch (const std::exception& e)
    {
      evalError = firstLine(e.what());
      progress("roi-graphslam: warning: evaluation failed: " + evalError);
    }
  }

  // Trajectory, graph, per-frame log.
  io::saveTumTrajectory(
      out + "trajectory.txt", estimate,
      "roi-graphslam " + src->name() + " mode " + frontend::toString(m_config.frontEnd.mode));
  try
  {
    graph.saveToTextFile(out + "graph.graph.tmp");
  }
  catch (const std::exception& e)
  {
    throw std::runtime_error(out + "graph.graph: " + firstLine(e.what()));
  }
  renameOrThrow(out + "graph.graph.tmp", out + "graph.graph");
  {
    std::ostringstream csv;
    csv << "index,timestamp,method,features,features_with_depth,roi_features,tracking_features,"
           "matches,inliers,roi_x,roi_y,roi_w,roi_h,keyframe,reference_keyframe,roi_ms,"
           "extract_ms,lift_ms,match_ms,ransac_ms,icp_ms,keyframe_ms,frontend_ms,backend_ms,"
           "sigma_t_mm,sigma_r_deg,icp_refined\n";
    csv << std::setprecision(6) << std::fixed;
    for (const auto& r : records)
    {
      const auto& f = r.result;
      const auto& t = f.times;
      csv << f.frameIndex << "," << f.timestamp << "," << frontend::toString(f.method) << ","
          << f.features << "," << f.featuresWithDepth << "," << f.roiFeatures << ","
          << f.trackingFeatures << "," << f.matches << "," << f.inliers << ",";
      if (f.roi)
        csv << f.roi->x << "," << f.roi->y << "," << f.roi->width << "," << f.roi->height << ",";
      else
        csv << ",,,,";
      csv << (f.isNewKeyframe ? std::to_string(f.newKeyframeId) : std::string()) << ","
          << f.referenceKeyframe << "," << t.roi_ms << "," << t.extract_ms << "," << t.lift_ms
          << "," << t.match_ms << "," << t.ransac_ms << "," << t.icp_ms << "," << t.keyframe_ms
          << "," << t.total_ms << "," << r.backendMs << ",";
      // The registration's worst-case 1-sigma (largest axis of the marginal
      // covariance): shows how well a (small) ROI constrains the pose.
      const auto sd = frontend::worstSigmas(f.relativeInformation);
      if (sd && f.method != frontend::ETrackingMethod::Initial &&
          f.method != frontend::ETrackingMethod::Lost)
        csv << 1e3 * sd->translation_m << "," << sd->rotation_rad * 180.0 / M_PI << ",";
      else
        csv << ",,";
      csv << (f.icpRefined ? 1 : 0) << "\n";
    }
    writeTextFile(out + "frames.csv", csv.str());
  }

  // Map: OctoMap (5 cm) from the keyframes' decimated clouds in the world frame.
  mrpt::system::CTicTac mapTimer;
  viz::TSceneContent content;
  {
    octomap::OcTree tree(0.05);
    const auto& clouds = ctx->keyframeClouds();
    std::size_t total = 0;
    for (const auto& c : clouds)
      total += c.size();
    const std::size_t sceneStep = std::max<std::size_t>(1, total / 400000 + 1);
    std::size_t counter = 0;
    for (std::size_t k = 0; k < clouds.size(); ++k)
    {
      const auto pose = pipeline.keyframePose(k);
      octomap::Pointcloud pc;
      pc.reserve(clouds[k].size());
      for (std::size_t i = 0; i < clouds[k].size(); ++i)
      {
        float x, y, z, r, g, b;
        clouds[k].getPointRGB(i, x, y, z, r, g, b);
        double wx, wy, wz;
        pose.composePoint(x, y, z, wx, wy, wz);
        pc.push_back(static_cast<float>(wx), static_cast<float>(wy), static_cast<float>(wz));
        if (counter++ % sceneStep == 0)
          content.cloud.insertPointRGB(
              static_cast<float>(wx), static_cast<float>(wy), static_cast<float>(wz), r, g, b);
      }
      const auto t = pose.translation();
      tree.insertPointCloud(pc, octomap::point3d(t.x, t.y, t.z), -1, false, true);
    }
    const std::string tmp = out + "map.bt.tmp";
    if (!tree.writeBinary(tmp))
      throw std::runtime_error(out + "map.bt: cannot write");
    renameOrThrow(tmp, out + "map.bt");
  }
  s.mapS = mapTimer.Tac();

  // Scene and snapshot.
  mrpt::system::CTicTac snapTimer;
  for (const auto& p : estimate)
    content.trajectory.push_back(p.pose.translation());
  if (eval)
  {
    // Ground truth shown in the estimate's frame.
    const auto toEstimate = -eval->ate.alignment;
    for (const auto& p : io::loadTumTrajectory(*src->groundTruthFile()))
      content.groundTruth.push_back((toEstimate + p.pose).translation());
  }
  auto scene = viz::CSlamSceneBuilder().build(content);
  viz::CSlamSceneBuilder::save(*scene, out + "scene.3Dscene");
  std::string snapshotError;
  if (m_args.snapshot)
  {
    try
    {
      viz::CSnapshotRenderer().renderToFile(*scene, out + "snapshot.png");
    }
    catch (const std::exception& e)
    {
      snapshotError = firstLine(e.what());
      progress("roi-graphslam: warning: no snapshot: " + snapshotError);
    }
  }
  s.snapshotS = snapTimer.Tac();
  s.peakRssMb = peakRssMb();

  nlohmann::json j;
  j["sequence"] = src->name();
  j["input"] = m_args.input;
  j["mode"] = frontend::toString(m_config.frontEnd.mode);
  j["feature"] = features::toString(m_config.frontEnd.extractor.feature_type);
  j["max_features"] = m_config.frontEnd.extractor.max_features;
  j["strict_roi"] = m_config.frontEnd.strict_roi;
  j["frames"] = s.frames;
  j["skipped_frames"] = src->skippedFrames();
  j["keyframes"] = s.keyframes;
  j["loop_closures"] = s.loopClosures;
  std::size_t lmLoops = 0;
  for (const auto& lc : ctx->loopClosures())
    lmLoops += lc.source == ELoopSource::Landmark;
  j["loop_closures_landmark"] = lmLoops;
  j["loop_closures_proximity"] = s.loopClosures - lmLoops;
  j["loop_closures_rejected"] = ctx->rejectedLoopClosures();
  j["landmarks"] = ctx->database().size();
  j["graph_nodes"] = graph.nodes.size();
  j["graph_edges"] = graph.edges.size();
  j["optimizations"] = optimizations;
  j["optimizations_windowed"] = windowedOptimizations;
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
  j["failed"] = s.failed;
  j["wall_s"] = s.wallS;
  j["fps"] = s.fps;
  j["map_s"] = s.mapS;
  j["snapshot_s"] = m_args.snapshot ? nlohmann::json(s.snapshotS) : nlohmann::json(nullptr);
  j["peak_rss_mb"] = s.peakRssMb;
  j["ate_rmse"] = optionalJson(s.ateRmse);
  j["rpe_trans_rmse"] = optionalJson(s.rpeTransRmse);
  j["rpe_rot_rmse_deg"] = optionalJson(s.rpeRotRmseDeg);
  j["frontend_ate_rmse"] = optionalJson(odometryAte);
  j["evaluation"] = eval ? evaluation::toJson(*eval) : nlohmann::json(nullptr);
  if (!evalError.empty())
    j["evaluation_error"] = evalError;
  if (!snapshotError.empty())
    j["snapshot_error"] = snapshotError;
  writeTextFile(out + "summary.json", j.dump(2) + "\n");
  return s;
}
}  // namespace roislam::graphslam
