#include <mrpt/system/CTicTac.h>
#include <octomap/OcTree.h>
#include <roislam/common/ErrorText.h>
#include <roislam/evaluation/CErrorPlot.h>
#include <roislam/evaluation/CTrajectoryPlot.h>
#include <roislam/frontend/PoseUncertainty.h>
#include <roislam/graphslam/CSlamOutputWriter.h>
#include <roislam/io/GraphText.h>
#include <roislam/viz/CSlamSceneBuilder.h>
#include <roislam/viz/CSnapshotRenderer.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace roislam::graphslam
{
namespace
{
/** Ground truth drawn this far (s) beyond the run's first and last frames. */
constexpr double kGroundTruthSlackS = 0.05;

std::string fixedText(double v, int decimals)
{
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

/** The snapshot's legend: sequence, front end, accuracy, which way is up. */
std::vector<std::string> legend(
    const CSlamOutputWriter::TRun& run, const CSlamOutputWriter::TReference& reference,
    const CGravityFrame::TResult& frame)
{
  const auto& fe = run.context.config().frontEnd;
  std::vector<std::string> lines{
      reference.sequence,
      "mode " + frontend::toString(fe.mode) + ", " + features::toString(fe.extractor.feature_type)};
  if (reference.evaluation)
    lines.push_back("ATE RMSE " + fixedText(reference.evaluation->ate.rmse, 4) + " m");
  else
    lines.push_back("ATE n/a (no ground truth)");
  const char* up[] = {"up: ground truth's z", "up: accelerometer", "up: first camera's -y"};
  lines.push_back(up[static_cast<int>(frame.source)]);
  return lines;
}

void renameOrThrow(const std::string& tmp, const std::string& file)
{
  if (std::rename(tmp.c_str(), file.c_str()) != 0)
  {
    std::remove(tmp.c_str());
    throw std::runtime_error(file + ": cannot rename from " + tmp);
  }
}

const char* kFramesCsvHeader =
    "index,timestamp,method,features,features_with_depth,roi_features,tracking_features,"
    "matches,inliers,roi_x,roi_y,roi_w,roi_h,keyframe,reference_keyframe,roi_ms,"
    "extract_ms,lift_ms,match_ms,ransac_ms,icp_ms,keyframe_ms,frontend_ms,backend_ms,"
    "sigma_t_mm,sigma_r_deg,icp_refined,region_x,region_y,region_w,region_h,region_pixels,"
    "region_features,extension_pixels,extension_features,extension,flow_tracks,flow_ms,"
    "icp_pair_share,icp_scale,bridged,feature_scale,icp_joint_scale\n";

void writeFramesCsvRow(std::ostream& csv, const CSlamPipeline::TFrameRecord& r)
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
      << f.referenceKeyframe << "," << t.roi_ms << "," << t.extract_ms << "," << t.lift_ms << ","
      << t.match_ms << "," << t.ransac_ms << "," << t.icp_ms << "," << t.keyframe_ms << ","
      << t.total_ms << "," << r.backendMs << ",";
  // The registration's worst-case 1-sigma (largest axis of the marginal
  // covariance): shows how well a (small) ROI constrains the pose.
  const auto sd = frontend::worstSigmas(f.relativeInformation);
  if (sd && f.method != frontend::ETrackingMethod::Initial &&
      f.method != frontend::ETrackingMethod::Lost)
    csv << 1e3 * sd->translation_m << "," << sd->rotation_rad * 180.0 / M_PI << ",";
  else
    csv << ",,";
  csv << (f.icpRefined ? 1 : 0) << ",";
  const auto& w = f.work;
  if (!w.region.empty())
    csv << w.region.x << "," << w.region.y << "," << w.region.width << "," << w.region.height;
  else
    csv << ",,,";
  csv << "," << w.regionPixels << "," << w.regionFeatures << "," << w.extensionPixels << ","
      << w.extensionFeatures << "," << frontend::toString(w.extension) << "," << f.flowTracks << ","
      << t.flow_ms << "," << f.icpPairShare << ",";
  if (f.icpScale > 0)
    csv << f.icpScale;
  csv << "," << (f.bridged ? 1 : 0) << ",";
  if (f.featureScale > 0)
    csv << f.featureScale << "," << f.icpJointScale;
  else
    csv << ",";
  csv << "\n";
}
}  // namespace

namespace
{
common::COutputFolder::TOptions folderOptions(bool overwrite)
{
  common::COutputFolder::TOptions o;
  o.overwrite = overwrite;
  o.known = CSlamOutputWriter::files();
  // The live view's key-press screenshots (CSlamObserver::onOutputFolder).
  o.knownPrefixes = {"screenshot-"};
  return o;
}
}  // namespace

const std::vector<std::string>& CSlamOutputWriter::files()
{
  static const std::vector<std::string> names{
      "trajectory.txt", "graph.graph", "map.bt",     "scene.3Dscene", "snapshot.png",
      "frames.csv",     "ate.png",     "errors.png", "report.txt",    "summary.json"};
  return names;
}

CSlamOutputWriter::CSlamOutputWriter(const std::string& outputDir, bool overwrite)
    : m_folder(outputDir, folderOptions(overwrite)), m_dir(m_folder.path() + "/")
{
}

void CSlamOutputWriter::writeReport(const std::string& text) const
{
  writeTextFile(m_dir + "report.txt", text);
}

void CSlamOutputWriter::writeTextFile(const std::string& file, const std::string& text)
{
  const std::string tmp = file + ".tmp";
  {
    std::ofstream out(tmp);
    out << text;
    out.flush();
    if (!out)
      throw std::runtime_error(file + ": cannot write");
  }
  renameOrThrow(tmp, file);
}

void CSlamOutputWriter::writeTrajectory(
    const io::TTrajectory& estimate, const std::string& header) const
{
  io::saveTumTrajectory(m_dir + "trajectory.txt", estimate, header);
}

void CSlamOutputWriter::writeGraph(const TGraph& graph) const
{
  // Not MRPT's saveToTextFile: it prints 6 significant digits (GraphText.h).
  io::saveGraphText(graph, m_dir + "graph.graph");
}

void CSlamOutputWriter::writeFramesCsv(
    const std::vector<CSlamPipeline::TFrameRecord>& records) const
{
  std::ostringstream csv;
  csv << kFramesCsvHeader << std::setprecision(6) << std::fixed;
  for (const auto& r : records)
    writeFramesCsvRow(csv, r);
  writeTextFile(m_dir + "frames.csv", csv.str());
}

viz::TSceneContent CSlamOutputWriter::writeMap(
    const TRun& run, const mrpt::poses::CPose3D& toDisplay) const
{
  viz::TSceneContent content;
  octomap::OcTree tree(0.05);
  const auto& clouds = run.context.keyframeClouds();
  std::size_t total = 0;
  for (const auto& c : clouds)
    total += c.size();
  // The scene keeps at most ~400k points (SceneViewer3D and the snapshot).
  const std::size_t sceneStep = std::max<std::size_t>(1, total / 400000 + 1);
  std::size_t counter = 0;
  for (std::size_t k = 0; k < clouds.size(); ++k)
  {
    const auto pose = toDisplay + run.keyframePose(k);
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
    // COctoMap ignores sensorPose in MRPT 2.5, so the clouds go in already in
    // the world frame, with the keyframe's position as the rays' origin.
    const auto t = pose.translation();
    tree.insertPointCloud(pc, octomap::point3d(t.x, t.y, t.z), -1, false, true);
  }
  const std::string tmp = m_dir + "map.bt.tmp";
  if (!tree.writeBinary(tmp))
    throw std::runtime_error(m_dir + "map.bt: cannot write");
  renameOrThrow(tmp, m_dir + "map.bt");
  return content;
}

std::string CSlamOutputWriter::writeScene(const viz::TSceneContent& content, bool snapshot) const
{
  auto scene = viz::CSlamSceneBuilder().build(content);
  viz::CSlamSceneBuilder::save(*scene, m_dir + "scene.3Dscene");
  if (!snapshot)
    return {};
  try
  {
    viz::CSnapshotRenderer().renderToFile(content, m_dir + "snapshot.png");
  }
  catch (const std::exception& e)
  {
    return common::firstLine(e.what());
  }
  return {};
}

std::string CSlamOutputWriter::writePlots(const TReference& reference) const
{
  const std::string ate = m_dir + "ate.png", errors = m_dir + "errors.png";
  // The folder is a fresh staging folder (COutputFolder): no plot of an
  // earlier run can remain beside these.
  if (!reference.evaluation)
    return {};
  const auto& ev = *reference.evaluation;
  std::string error;
  try
  {
    evaluation::CTrajectoryPlot::TOptions po;
    po.title = reference.sequence + ": ground truth and the aligned estimate (ATE RMSE " +
               fixedText(ev.ate.rmse, 4) + " m)";
    evaluation::CTrajectoryPlot(po).plot(
        ate, reference.groundTruth, {{"estimate (aligned)", ev.aligned}});
  }
  catch (const std::exception& e)
  {
    error = common::firstLine(e.what());
  }
  try
  {
    evaluation::CErrorPlot::TOptions eo;
    eo.title = reference.sequence + ": errors over time";
    evaluation::CErrorPlot(eo).plot(errors, ev);
  }
  catch (const std::exception& e)
  {
    if (error.empty())
      error = common::firstLine(e.what());
  }
  return error;
}

std::vector<std::string> CSlamOutputWriter::TPictures::warnings() const
{
  std::vector<std::string> w;
  if (!snapshotError.empty())
    w.push_back("no snapshot: " + snapshotError);
  if (!plotError.empty())
    w.push_back("no error plots: " + plotError);
  if (!frame.note.empty())
    w.push_back("pictures not levelled by the accelerometer: " + frame.note);
  return w;
}

void CSlamOutputWriter::TPictures::addToSummary(nlohmann::json& summary) const
{
  summary["display_frame"] = frame.toJson();
  if (!snapshotError.empty())
    summary["snapshot_error"] = snapshotError;
  if (!plotError.empty())
    summary["plot_error"] = plotError;
}

CSlamOutputWriter::TPictures CSlamOutputWriter::writePictures(
    const TRun& run, const TReference& reference, bool snapshot) const
{
  TPictures out;
  const auto* ev = reference.evaluation;
  out.frame = CGravityFrame::choose(
      reference.estimate,
      ev ? std::optional<mrpt::poses::CPose3D>(ev->ate.alignment) : std::nullopt,
      reference.accelerometerFile);
  const auto& toDisplay = out.frame.toDisplay;

  mrpt::system::CTicTac mapTimer;
  viz::TSceneContent content = writeMap(run, toDisplay);
  out.mapS = mapTimer.Tac();

  mrpt::system::CTicTac snapTimer;
  for (const auto& p : reference.estimate)
  {
    const auto pose = toDisplay + p.pose;
    content.trajectory.push_back(pose.translation());
    const auto R = pose.getRotationMatrix();
    content.lookDirection =
        content.lookDirection + mrpt::math::TVector3D(R(0, 2), R(1, 2), R(2, 2));
  }
  for (std::size_t k = 0; k < run.context.keyframeClouds().size(); ++k)
    content.keyframes.push_back((toDisplay + run.keyframePose(k)).translation());
  if (ev)
  {
    // The ground truth in the display frame: back through the alignment.
    // The ground truth in the display frame (back through the alignment),
    // over the run's span only (TUM files start and end a second around it).
    const auto gtToDisplay = toDisplay + (-ev->ate.alignment);
    const double t0 = reference.estimate.front().timestamp;
    const double t1 = reference.estimate.back().timestamp;
    for (const auto& p : reference.groundTruth)
      if (p.timestamp >= t0 - kGroundTruthSlackS && p.timestamp <= t1 + kGroundTruthSlackS)
        content.groundTruth.push_back((gtToDisplay + p.pose).translation());
  }
  content.legend = legend(run, reference, out.frame);
  out.snapshotError = writeScene(content, snapshot);
  out.plotError = writePlots(reference);
  out.snapshotS = snapTimer.Tac();
  return out;
}

void CSlamOutputWriter::writeSummary(const nlohmann::json& summary)
{
  writeTextFile(m_dir + "summary.json", summary.dump(2) + "\n");
  m_folder.commit();
  m_dir = m_folder.path() + "/";
}
}  // namespace roislam::graphslam
