#include <mrpt/containers/yaml.h>
#include <mrpt/graphslam/levmarq.h>
#include <mrpt/system/CTicTac.h>
#include <roislam/common/IniErrors.h>
#include <roislam/common/Median.h>
#include <roislam/evaluation/EdgeChi2.h>
#include <roislam/graphslam/CSlamContext.h>
#include <roislam/graphslam/SlamIni.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <utility>

namespace roislam::graphslam
{

std::string toString(ELoopSource s)
{
  return s == ELoopSource::Landmark ? "landmark" : "proximity";
}

void CSlamContext::TOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& s)
{
  loop_min_keyframe_gap = c.read_int(s, "loop_min_keyframe_gap", loop_min_keyframe_gap);
  landmark_loops = c.read_bool(s, "landmark_loops", landmark_loops);
  proximity_loops = c.read_bool(s, "proximity_loops", proximity_loops);
  proximity_radius_m = c.read_double(s, "proximity_radius_m", proximity_radius_m);
  proximity_max_angle_deg = c.read_double(s, "proximity_max_angle_deg", proximity_max_angle_deg);
  max_loop_candidates = c.read_int(s, "max_loop_candidates", max_loop_candidates);
  loop_min_inliers = c.read_int(s, "loop_min_inliers", loop_min_inliers);
  loop_max_discrepancy_m = c.read_double(s, "loop_max_discrepancy_m", loop_max_discrepancy_m);
  loop_max_discrepancy_per_m =
      c.read_double(s, "loop_max_discrepancy_per_m", loop_max_discrepancy_per_m);
  optimizer_max_iterations = c.read_int(s, "optimizer_max_iterations", optimizer_max_iterations);
  loop_outlier_chi2 = c.read_double(s, "loop_outlier_chi2", loop_outlier_chi2);
  optimize_min_chi2 = c.read_double(s, "optimize_min_chi2", optimize_min_chi2);
  optimize_every_keyframes = c.read_int(s, "optimize_every_keyframes", optimize_every_keyframes);
  optimize_window_keyframes = c.read_int(s, "optimize_window_keyframes", optimize_window_keyframes);
  map_decimation = c.read_int(s, "map_decimation", map_decimation);
  map_max_depth_m = c.read_double(s, "map_max_depth_m", map_max_depth_m);
  edge_information = c.read_string(s, "edge_information", edge_information);
  edge_sigma_m = c.read_double(s, "edge_sigma_m", edge_sigma_m);
  edge_sigma_deg = c.read_double(s, "edge_sigma_deg", edge_sigma_deg);
  validate(s);
}

void CSlamContext::TOptions::saveToConfigFile(
    mrpt::config::CConfigFileBase& c, const std::string& s) const
{
  c.write(s, "loop_min_keyframe_gap", loop_min_keyframe_gap);
  c.write(s, "landmark_loops", landmark_loops);
  c.write(s, "proximity_loops", proximity_loops);
  c.write(s, "proximity_radius_m", proximity_radius_m);
  c.write(s, "proximity_max_angle_deg", proximity_max_angle_deg);
  c.write(s, "max_loop_candidates", max_loop_candidates);
  c.write(s, "loop_min_inliers", loop_min_inliers);
  c.write(s, "loop_max_discrepancy_m", loop_max_discrepancy_m);
  c.write(s, "loop_max_discrepancy_per_m", loop_max_discrepancy_per_m);
  c.write(s, "optimizer_max_iterations", optimizer_max_iterations);
  c.write(s, "loop_outlier_chi2", loop_outlier_chi2);
  c.write(s, "optimize_min_chi2", optimize_min_chi2);
  c.write(s, "optimize_every_keyframes", optimize_every_keyframes);
  c.write(s, "optimize_window_keyframes", optimize_window_keyframes);
  c.write(s, "map_decimation", map_decimation);
  c.write(s, "map_max_depth_m", map_max_depth_m);
  c.write(s, "edge_information", edge_information);
  c.write(s, "edge_sigma_m", edge_sigma_m);
  c.write(s, "edge_sigma_deg", edge_sigma_deg);
}

void CSlamContext::TOptions::validate(const std::string& section) const
{
  const auto badKey = [&section](const std::string& key, const std::string& why)
  { common::throwBadIniKey(section, key, why); };
  if (loop_min_keyframe_gap < 1)
    badKey("loop_min_keyframe_gap", "must be >= 1");
  if (!(proximity_radius_m > 0))
    badKey("proximity_radius_m", "must be > 0");
  if (!(proximity_max_angle_deg > 0))
    badKey("proximity_max_angle_deg", "must be > 0");
  if (max_loop_candidates < 1)
    badKey("max_loop_candidates", "must be >= 1");
  if (loop_min_inliers < 3)
    badKey("loop_min_inliers", "must be >= 3");
  if (!(loop_max_discrepancy_m > 0))
    badKey("loop_max_discrepancy_m", "must be > 0");
  if (!(loop_max_discrepancy_per_m >= 0))
    badKey("loop_max_discrepancy_per_m", "must be >= 0");
  if (optimizer_max_iterations < 1)
    badKey("optimizer_max_iterations", "must be >= 1");
  if (!(loop_outlier_chi2 > 0))
    badKey("loop_outlier_chi2", "must be > 0");
  if (!(optimize_min_chi2 >= 0))
    badKey("optimize_min_chi2", "must be >= 0");
  if (optimize_every_keyframes < 1)
    badKey("optimize_every_keyframes", "must be >= 1");
  if (optimize_window_keyframes < 0)
    badKey("optimize_window_keyframes", "must be >= 0");
  if (edge_information != "frontend" && edge_information != "diagonal" &&
      edge_information != "estimator")
    badKey(
        "edge_information",
        "unknown value '" + edge_information + "' (expected estimator, frontend or diagonal)");
  if (map_decimation < 1)
    badKey("map_decimation", "must be >= 1");
  if (!(map_max_depth_m > 0))
    badKey("map_max_depth_m", "must be > 0");
}

namespace
{
/** The landmark pipeline's options for the back end's database: its
 *  database and homography settings, the front end's matcher. */
landmarks::TPipelineOptions landmarkOptions(const CSlamContext::TConfig& config)
{
  landmarks::TPipelineOptions o;
  o.database = config.database;
  o.matcher = config.frontEnd.matcher;
  o.locator = config.locator;
  o.roi = config.frontEnd.roi;
  o.features = config.frontEnd.extractor;
  return o;
}

/** The median of chi-square with 6 degrees of freedom (a pose edge's). */
constexpr double kChi2Median6 = 5.348;
}  // namespace

CSlamContext::CSlamContext() : CSlamContext(TConfig()) {}

CSlamContext::CSlamContext(const TConfig& config, EConfigOrigin origin) : m_origin(origin)
{
  configure(config);
}

void CSlamContext::configure(const TConfig& config)
{
  if (m_framesRecorded > 0)
    throw std::logic_error("CSlamContext::configure: the run has started");
  config.backEnd.validate();
  auto odometry = std::make_unique<frontend::CRgbdOdometry>(config.frontEnd);
  auto landmarks = std::make_unique<landmarks::CObservationProcessor>(landmarkOptions(config));
  m_config = config;
  m_odometry = std::move(odometry);
  m_landmarks = std::move(landmarks);
}

void CSlamContext::recordFrame(const frontend::TFrameResult& result, const io::TRGBDFrame& frame)
{
  ++m_framesRecorded;
  m_last = result;
  m_imageSize = frame.rgb.size();
  if (!result.isNewKeyframe)
    return;
  // Map cloud of the keyframe, in its optical frame (decimated: the OctoMap
  // insertion cost grows with the number of rays).
  const auto& cam = frame.camera;
  const int step = m_config.backEnd.map_decimation;
  mrpt::maps::CColouredPointsMap cloud;
  cloud.reserve((frame.depth.rows / step + 1) * (frame.depth.cols / step + 1));
  for (int v = 0; v < frame.depth.rows; v += step)
  {
    const float* d = frame.depth.ptr<float>(v);
    const cv::Vec3b* c = frame.rgb.ptr<cv::Vec3b>(v);
    for (int u = 0; u < frame.depth.cols; u += step)
    {
      const float z = d[u];
      if (!(z > 0) || z > m_config.backEnd.map_max_depth_m)
        continue;
      const float x = static_cast<float>((u - cam.cx()) * z / cam.fx());
      const float y = static_cast<float>((v - cam.cy()) * z / cam.fy());
      cloud.insertPointRGB(x, y, z, c[u][2] / 255.f, c[u][1] / 255.f, c[u][0] / 255.f);
    }
  }
  m_clouds.resize(result.newKeyframeId + 1);
  m_clouds[result.newKeyframeId] = std::move(cloud);
}

double CSlamContext::loopDiscrepancyLimit(
    std::size_t from, std::size_t to, const TGraph& graph) const
{
  const auto& o = m_config.backEnd;
  double path = 0;
  for (std::size_t k = std::min(from, to); k < std::max(from, to); ++k)
  {
    const auto a = graph.nodes.find(k), b = graph.nodes.find(k + 1);
    if (a != graph.nodes.end() && b != graph.nodes.end())
      path += (b->second.translation() - a->second.translation()).norm();
  }
  return o.loop_max_discrepancy_m + o.loop_max_discrepancy_per_m * path;
}

std::optional<int32_t> CSlamContext::observeLandmarks(std::size_t id)
{
  std::optional<int32_t> recalled;
  if (!m_config.backEnd.landmark_loops)
    return recalled;
  for (std::size_t k = m_landmarkQueried; k <= id && k < m_odometry->keyframes().size(); ++k)
  {
    m_landmarkQueried = k + 1;
    const auto& kf = m_odometry->keyframe(k);
    if (!kf.roi)
      continue;
    const auto roiFeatures = kf.features.subset(*kf.roi);
    if (roiFeatures.size() < 10)
      continue;
    landmarks::TRegion region;
    region.frame = kf.frameIndex;
    region.timestamp = kf.timestamp;
    region.box = *kf.roi;
    region.imageSize = m_imageSize;
    region.features = roiFeatures;
    const auto seen = m_landmarks->processRegion(region).result;
    const int32_t lm = seen.landmarkId;
    if (!seen.newLandmark && k == id)
      recalled = lm;
    m_sightings[lm].push_back(k);
  }
  return recalled;
}

std::vector<std::pair<std::size_t, ELoopSource>> CSlamContext::loopCandidates(
    std::size_t id, std::optional<int32_t> recalledLandmark, const TGraph& graph) const
{
  const auto& o = m_config.backEnd;
  std::vector<std::pair<std::size_t, ELoopSource>> out;
  auto already = [&](std::size_t k)
  { return std::any_of(out.begin(), out.end(), [&](const auto& p) { return p.first == k; }); };
  const std::size_t gap = static_cast<std::size_t>(o.loop_min_keyframe_gap);
  const std::size_t maxCandidates = static_cast<std::size_t>(o.max_loop_candidates);

  if (recalledLandmark && m_sightings.count(*recalledLandmark))
  {
    // Most recent earlier sightings first: their relative pose is the most
    // likely to register.
    const auto& seen = m_sightings.at(*recalledLandmark);
    for (auto it = seen.rbegin(); it != seen.rend() && out.size() < maxCandidates; ++it)
      if (*it + gap <= id && !already(*it))
        out.emplace_back(*it, ELoopSource::Landmark);
  }
  if (!o.proximity_loops || id < gap || !graph.nodes.count(id))
    return out;
  const auto& cur = graph.nodes.at(id);
  const double cosMax = std::cos(o.proximity_max_angle_deg * M_PI / 180.0);
  std::vector<std::pair<double, std::size_t>> near;
  for (std::size_t k = 0; k + gap <= id; ++k)
  {
    const auto it = graph.nodes.find(k);
    if (it == graph.nodes.end())
      continue;
    const double d = (it->second.translation() - cur.translation()).norm();
    if (d > o.proximity_radius_m)
      continue;
    // Optical axes (third rotation column) must look roughly the same way.
    const auto R1 = it->second.getRotationMatrix(), R2 = cur.getRotationMatrix();
    const double c = R1(0, 2) * R2(0, 2) + R1(1, 2) * R2(1, 2) + R1(2, 2) * R2(2, 2);
    if (c >= cosMax)
      near.emplace_back(d, k);
  }
  std::sort(near.begin(), near.end());
  std::size_t added = 0;
  for (const auto& [d, k] : near)
  {
    if (added >= maxCandidates)
      break;
    if (already(k))
      continue;
    out.emplace_back(k, ELoopSource::Proximity);
    ++added;
  }
  return out;
}

frontend::TInformation66 CSlamContext::edgeInformation(
    const frontend::TInformation66& frontEndInformation, frontend::ETrackingMethod method,
    std::size_t inliers, const frontend::TInformation66& estimatorInformation) const
{
  const auto& o = m_config.backEnd;
  if (o.edge_information == "estimator")
    return estimatorInformation;
  if (o.edge_information == "frontend" || method == frontend::ETrackingMethod::ConstantVelocity)
    return frontEndInformation;
  // Isotropic blocks also sidestep the (yaw, pitch, roll) vs rotation-vector
  // ordering difference between CPose3DPDFGaussianInf and the SE(3) solver.
  const double n = std::clamp(static_cast<double>(inliers), 10.0, 1000.0);
  const double scale = n / 100.0;  // information grows with the inliers
  const double st = o.edge_sigma_m, sr = o.edge_sigma_deg * M_PI / 180.0;
  frontend::TInformation66 info;
  info.setZero();
  for (int k = 0; k < 3; ++k)
    info(k, k) = scale / (st * st);
  for (int k = 3; k < 6; ++k)
    info(k, k) = scale / (sr * sr);
  return info;
}

TOptimizationReport CSlamContext::optimize(TGraph& graph, std::size_t window, bool measureChi2)
{
  TOptimizationReport r;
  if (graph.nodes.size() < 2 || graph.edges.empty())
    return r;
  mrpt::system::CTicTac timer;
  if (measureChi2)
    r.chi2Before = graph.chi2();
  // A window frees only the newest nodes; the older ones stay where the last
  // optimisation put them and anchor the new ones (MRPT solves only the free
  // nodes' block, so the cost no longer grows with the graph).
  std::set<mrpt::graphs::TNodeID> freeNodes;
  if (window > 0 && graph.nodes.size() > window + 1)
  {
    auto it = graph.nodes.end();
    for (std::size_t i = 0; i < window; ++i)
      freeNodes.insert((--it)->first);
    r.freeNodes = window;
  }
  else
    r.freeNodes = graph.nodes.size() - 1;
  const std::set<mrpt::graphs::TNodeID>* toOptimize = freeNodes.empty() ? nullptr : &freeNodes;
  mrpt::graphslam::TResultInfoSpaLevMarq info;
  mrpt::containers::yaml params = mrpt::containers::yaml::Map();
  params["max_iterations"] = static_cast<uint64_t>(m_config.backEnd.optimizer_max_iterations);
  mrpt::graphslam::optimize_graph_spa_levmarq(graph, info, toOptimize, params);
  r.iterations = info.num_iters;
  // A false closure stays inconsistent with everything else after the
  // optimisation: drop the worst such edges and solve again.
  // Only a whole-graph solution judges closures: with old nodes held fixed,
  // a good closure to them can still carry the error the window could not
  // spread.
  for (int round = 0; round < (toOptimize ? 0 : 3); ++round)
  {
    const std::vector<std::size_t> outliers = closureOutliers(graph);
    if (outliers.empty())
      break;
    for (auto k = outliers.rbegin(); k != outliers.rend(); ++k)
    {
      graph.edges.erase(graph.edges.find(m_loops[*k].edge()));
      m_loops.erase(m_loops.begin() + static_cast<std::ptrdiff_t>(*k));
      ++m_rejectedLoops;
    }
    mrpt::graphslam::optimize_graph_spa_levmarq(graph, info, toOptimize, params);
    r.iterations += info.num_iters;
  }
  if (measureChi2)
    r.chi2After = graph.chi2();
  r.seconds = timer.Tac();
  return r;
}

std::vector<std::size_t> CSlamContext::closureOutliers(const TGraph& graph)
{
  // The test is relative to how much the whole graph disagrees beyond its
  // information: with the estimators' information (edge_information =
  // estimator) on a real Kinect every edge claims 10-20x less spread than it
  // has, and an absolute threshold removed 11-20 closures a run on fr1/rpy
  // that the diagonal information, whose factor is 1, kept (0-1 removed).
  // The closures are also judged against each other: on fr1 with the
  // estimators' information the graph's median edge (a chain edge, whose
  // triangles with its neighbours agree) reads a factor of 1.0-1.3 while the
  // closures, which see the chain's drift, disagree by chi2 40-390, and the
  // graph's factor alone removed 11 of small ROI SURF's closures on fr1/rpy
  // (ATE 0.0113 -> 0.0264 m). The closures' own median keeps a few false
  // ones from hiding among many true ones.
  m_varianceFactor = graphVarianceFactor(graph);
  std::vector<double> loopChi2(m_loops.size(), -1);
  for (std::size_t i = 0; i < m_loops.size(); ++i)
  {
    const auto it = graph.edges.find(m_loops[i].edge());
    if (it != graph.edges.end())
      loopChi2[i] = edgeChi2(graph, it);
  }
  m_loopVarianceFactor = std::max(m_varianceFactor, closureVarianceFactor(loopChi2));
  std::vector<std::size_t> outliers;
  for (std::size_t i = 0; i < m_loops.size(); ++i)
    if (loopChi2[i] > m_config.backEnd.loop_outlier_chi2 * m_loopVarianceFactor)
      outliers.push_back(i);
  return outliers;
}

double CSlamContext::graphVarianceFactor(const TGraph& graph)
{
  const double edges = static_cast<double>(graph.edges.size());
  const double redundancy = 6 * edges - 6 * (static_cast<double>(graph.nodes.size()) - 1);
  if (!(redundancy > 0))
    return 1;
  std::vector<double> chi2;
  chi2.reserve(graph.edges.size());
  for (auto it = graph.edges.begin(); it != graph.edges.end(); ++it)
    chi2.push_back(edgeChi2(graph, it));
  const double expected = kChi2Median6 * redundancy / (6 * edges);
  return std::max(1.0, common::upperMedian(std::move(chi2)) / expected);
}

double CSlamContext::closureVarianceFactor(std::vector<double> closureChi2)
{
  closureChi2.erase(
      std::remove_if(closureChi2.begin(), closureChi2.end(), [](double c) { return c < 0; }),
      closureChi2.end());
  // Three closures at least: then the median is set by two that agree, and a
  // single false one cannot raise it.
  if (closureChi2.size() < 3)
    return 1;
  auto mid = closureChi2.begin() + static_cast<std::ptrdiff_t>((closureChi2.size() - 1) / 2);
  std::nth_element(closureChi2.begin(), mid, closureChi2.end());
  // A closure's redundancy is at most 1 (it is the only edge across its
  // cycle): kChi2Median6 is the most an honest closure reads, so the factor
  // errs towards keeping the test strict.
  return std::max(1.0, *mid / kChi2Median6);
}

double CSlamContext::edgeChi2(const TGraph& graph, TGraph::edges_map_t::const_iterator it)
{
  const auto& [ids, edge] = *it;
  return evaluation::edgeChi2(
      edge.mean, edge.cov_inv, graph.nodes.at(ids.second) - graph.nodes.at(ids.first));
}

void CSlamContext::correctFrontEnd(const TGraph& graph)
{
  std::map<std::size_t, mrpt::poses::CPose3D> poses;
  for (const auto& [id, pose] : graph.nodes)
    poses.emplace(static_cast<std::size_t>(id), pose);
  m_odometry->correctKeyframePoses(poses);
}
}  // namespace roislam::graphslam

namespace roislam::graphslam
{
CSlamContext::TConfig CSlamContext::loadConfig(
    const mrpt::config::CConfigFileBase& cfg, const std::string& fileLabel)
{
  TConfig c;
  for (const auto part :
       {ESlamParams::NodeRegistration, ESlamParams::EdgeRegistration, ESlamParams::Optimizer})
    loadSlamParams(cfg, fileLabel, part, c);
  return c;
}

CSlamContext& sharedContext(const std::shared_ptr<CSlamContext>& context, const char* decider)
{
  if (!context)
    throw std::logic_error(
        std::string(decider) +
        ": no CSlamContext shared with the other deciders; create roislam's deciders together "
        "with CRoislamOptionsChecker::createDeciders()");
  return *context;
}
}  // namespace roislam::graphslam
