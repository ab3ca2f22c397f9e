/* State shared by our node and edge registration deciders (CKeyframeNRD,
 * CKeyframeERD) and the optimiser (CKeyframeGSO): the front end
 * (CRgbdOdometry: one graph node per keyframe, node id == keyframe id), the
 * ROI landmark database used for loop-closure candidates, per-keyframe map
 * clouds, and the loop-closure bookkeeping. MRPT's engine gives each decider
 * only the graph, so the deciders hold a shared_ptr to one context, handed to
 * them with setContext() by whoever creates them together: the factory
 * CRoislamOptionsChecker::createDeciders() (deciders chosen by name), or a
 * test. The context lives as long as its deciders: nothing outlives the
 * engine that runs them.
 *
 * Its configuration is either given whole by its creator (roi-graphslam: ini
 * plus command line) or read piece by piece by the deciders' loadParams()
 * from the engine's ini (EConfigOrigin::DecidersLoadParams, configure()), in
 * roi-graphslam's layout or in MRPT's graph-SLAM sections (SlamIni.h).
 *
 * ini section [GraphSlam] (TOptions), units in brackets:
 *  - loop_min_keyframe_gap     int >= 1 (10): loop candidates are at least this
 *                              many keyframes older than the current one
 *  - landmark_loops            bool (true): candidates from ROI landmark recall
 *  - proximity_loops           bool (true): candidates near the current
 *                              keyframe in the current estimate
 *  - proximity_radius_m        [m] > 0 (0.4)
 *  - proximity_max_angle_deg   [deg] > 0 (35): viewing-direction difference
 *  - max_loop_candidates       int >= 1 (3): verified per keyframe and source
 *  - loop_min_inliers          int >= 3 (25): 3-D RANSAC inliers to accept
 *  - loop_max_discrepancy_m    [m] > 0 (0.5): reject a verified closure whose
 *                              relative pose disagrees with the estimate by more
 *                              (plus the allowance below)
 *  - loop_max_discrepancy_per_m  >= 0 (0.05): the limit grows by this much per
 *                              metre of estimated path between the two
 *                              keyframes: odometry drifts a few percent of the
 *                              distance travelled, so a fixed limit would
 *                              refuse the true closures of long loops (a 20 m
 *                              office loop at 2.5 % drift is already off by
 *                              0.5 m) while they are the ones that matter
 *  - loop_outlier_chi2         double > 0 (30): after an optimisation, a loop
 *                              edge whose squared Mahalanobis error exceeds
 *                              this times the closures' variance factor
 *                              (loopVarianceFactor()) is removed as a false
 *                              closure and the graph re-optimised (at most 3
 *                              rounds)
 *  - optimize_min_chi2         double >= 0 (30, as loop_outlier_chi2): a
 *                              keyframe whose new loop closure disagrees with
 *                              the current estimate by more (squared
 *                              Mahalanobis error, over the variance factor) is
 *                              optimised at once; 0 = at every loop closure
 *  - optimize_window_keyframes int >= 0 (50): such an optimisation moves only
 *                              the newest this many keyframes, the older ones
 *                              held fixed (its cost stays flat; it does not
 *                              judge closures, the whole-graph ones do).
 *                              0 = solve the whole graph, once graph nodes /
 *                              50 keyframes with closures are pending
 *  - optimize_every_keyframes  int >= 1 (10): other closures are optimised
 *                              together once max(this, graph nodes / 10)
 *                              keyframes brought some (and always at the
 *                              end). Each of these solves the whole
 *                              graph, so its cost grows with it: optimising
 *                              at every closure cost 35 ms a frame after 750
 *                              frames (fr1/rpy there and back, 229 nodes);
 *                              spacing that grows with the graph keeps the
 *                              cost per frame flat
 *  - optimizer_max_iterations  int >= 1 (50): Levenberg-Marquardt (SPA) limit
 *  - map_decimation            int >= 1 (8): every n-th pixel/row of a
 *                              keyframe's depth goes into the map cloud
 *  - map_max_depth_m           [m] > 0 (4.0): farther readings are not mapped
 *  - edge_information          estimator|frontend|diagonal (estimator): edge
 *                              weights as the estimator's information in
 *                              SPA's parametrisation (reprojection with pixel
 *                              and depth noise, variance factor of the fit;
 *                              ICP's point-to-plane Hessian), as the front
 *                              end's tracking gates see it (pixel noise only,
 *                              very confident: sigma ~0.3 mm), or diagonal
 *                              from the two sigmas below, scaled by
 *                              sqrt(100 / inliers) (10..1000 inliers).
 *                              estimator is the default since its closures
 *                              are judged against their own variance factor
 *                              (README "Edge information"): honest on
 *                              synthetic data and more accurate there (45
 *                              runs: x0.32-0.95), within -10..+9 % of
 *                              diagonal on fr1, where every edge claims
 *                              10-20x too little spread
 *  - edge_sigma_m              [m] > 0 (0.01): diagonal's translation sigma
 *                              at 100 inliers
 *  - edge_sigma_deg            [deg] > 0 (0.5): diagonal's rotation sigma at
 *                              100 inliers
 * In MRPT's layout (roi-graphslam-engine) the same keys live in
 * [GeneralConfiguration] (map_*, edge_*), [EdgeRegistrationDeciderParameters]
 * (loop_*, landmark_loops, proximity_*, max_loop_candidates) and
 * [OptimizerParameters] (optimizer_max_iterations, loop_outlier_chi2,
 * optimize_*), see SlamIni.h and config/graphslam-engine.ini.
 * A bad value throws std::invalid_argument "[GraphSlam] key: why" (the
 * section the key was read from).
 */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/graphs/CNetworkOfPoses.h>
#include <mrpt/maps/CColouredPointsMap.h>
#include <roislam/frontend/CRgbdOdometry.h>
#include <roislam/io/TRGBDFrame.h>
#include <roislam/landmarks/CLandmarkDatabase.h>
#include <roislam/landmarks/CObservationProcessor.h>

#include <cstddef>
#include <map>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace roislam::graphslam
{
using TGraph = mrpt::graphs::CNetworkOfPoses3DInf;

/** Where a loop-closure candidate came from. */
enum class ELoopSource
{
  Landmark,
  Proximity
};

/** One accepted loop-closure edge. */
struct TLoopClosure
{
  std::size_t fromKeyframe = 0, toKeyframe = 0;
  ELoopSource source = ELoopSource::Proximity;
  std::size_t inliers = 0;
  /** Its edge's key in the graph (node id == keyframe id). */
  std::pair<mrpt::graphs::TNodeID, mrpt::graphs::TNodeID> edge() const
  {
    return {
        static_cast<mrpt::graphs::TNodeID>(fromKeyframe),
        static_cast<mrpt::graphs::TNodeID>(toKeyframe)};
  }
};

/** Summary of one graph optimisation. */
struct TOptimizationReport
{
  std::size_t iterations = 0;
  /** The whole graph's chi2 before and after; 0 when not measured
   *  (CSlamContext::optimize's measureChi2). */
  double chi2Before = 0, chi2After = 0;
  double seconds = 0;
  /** Nodes it moved (the others were held fixed). */
  std::size_t freeNodes = 0;
};

class CSlamContext
{
 public:
  struct TOptions : public mrpt::config::CLoadableOptions
  {
    int loop_min_keyframe_gap = 10;
    bool landmark_loops = true;
    bool proximity_loops = true;
    double proximity_radius_m = 0.4;
    double proximity_max_angle_deg = 35;
    int max_loop_candidates = 3;
    int loop_min_inliers = 25;
    double loop_max_discrepancy_m = 0.5;
    double loop_max_discrepancy_per_m = 0.05;
    int optimizer_max_iterations = 50;
    double loop_outlier_chi2 = 30;
    double optimize_min_chi2 = 30;
    int optimize_every_keyframes = 10;
    int optimize_window_keyframes = 50;
    int map_decimation = 8;
    double map_max_depth_m = 4.0;
    std::string edge_information = "estimator";
    double edge_sigma_m = 0.01;
    double edge_sigma_deg = 0.5;

    void loadFromConfigFile(
        const mrpt::config::CConfigFileBase& source, const std::string& section) override;
    void saveToConfigFile(
        mrpt::config::CConfigFileBase& target, const std::string& section) const override;
    /** Throws std::invalid_argument "[<section>] key: why"
     *  (loadFromConfigFile() names the section it read). */
    void validate(const std::string& section = "GraphSlam") const;
  };

  /** Everything the context is built from. */
  struct TConfig
  {
    TOptions backEnd;                                 // [GraphSlam]
    frontend::CRgbdOdometry::TOptions frontEnd;       // [FrontEnd] + sub-sections
    landmarks::CLandmarkDatabase::TOptions database;  // [LandmarkDatabase]
    matching::CHomographyLocator::TOptions locator;   // [HomographyLocator]
  };

  /** Who sets the configuration. */
  enum class EConfigOrigin
  {
    /** Given whole to the constructor; the deciders' loadParams() read
     *  nothing (roi-graphslam, tests). */
    Caller,
    /** Defaults until the deciders' loadParams() read their parts of the
     *  engine's ini into it (configure()). */
    DecidersLoadParams
  };

  CSlamContext();
  explicit CSlamContext(const TConfig& config, EConfigOrigin origin = EConfigOrigin::Caller);

  /** Reads every section of `cfg` (absent sections keep defaults), in either
   *  layout (SlamIni.h: roi-graphslam's [FrontEnd] / [GraphSlam], or MRPT's
   *  graph-SLAM sections), after checking that the sections hold only known
   *  keys: "ini <fileLabel>: [Section] unknown key 'x'". */
  static TConfig loadConfig(const mrpt::config::CConfigFileBase& cfg, const std::string& fileLabel);

  EConfigOrigin configOrigin() const { return m_origin; }
  /** Replaces the configuration (rebuilding the front end and the landmark
   *  database): the deciders' loadParams(), before the first frame. Throws
   *  std::invalid_argument on bad values, std::logic_error once a frame was
   *  recorded. */
  void configure(const TConfig& config);

  frontend::CRgbdOdometry& odometry() { return *m_odometry; }
  const frontend::CRgbdOdometry& odometry() const { return *m_odometry; }
  const landmarks::CLandmarkDatabase& database() const { return m_landmarks->tracker().database(); }
  const TConfig& config() const { return m_config; }

  /** Keeps what the back end needs of a front-end result: a new keyframe's
   *  map cloud (from the frame's depth and colour), and the result itself as
   *  lastFrame(). Called once per frame by whoever ran the front end
   *  (CSlamPipeline, or CKeyframeNRD inside MRPT's engine). */
  void recordFrame(const frontend::TFrameResult& result, const io::TRGBDFrame& frame);
  /** The result recordFrame() saw last: inside MRPT's engine, the hand-off
   *  from CKeyframeNRD to CKeyframeERD within one step (nullopt before the
   *  first). */
  const std::optional<frontend::TFrameResult>& lastFrame() const { return m_last; }
  /** Frames recordFrame() saw: tells the edge decider whether lastFrame() is
   *  new in this step. */
  std::size_t framesRecorded() const { return m_framesRecorded; }

  /** Puts the ROI of every keyframe up to `id` not yet seen into the ROI
   *  landmark database: a recall adds a sighting, else a new landmark is
   *  stored. Returns the landmark keyframe `id` recalled, if any. Called by
   *  CKeyframeERD for each new keyframe, before loopCandidates(). */
  std::optional<int32_t> observeLandmarks(std::size_t id);

  /** Loop-closure candidates for keyframe `id` (older than the gap): the
   *  earlier sightings of the landmark it recalled (observeLandmarks()),
   *  most recent first, and keyframes near it in `graph`. */
  std::vector<std::pair<std::size_t, ELoopSource>> loopCandidates(
      std::size_t id, std::optional<int32_t> recalledLandmark, const TGraph& graph) const;

  /** Largest translation discrepancy accepted between a verified closure
   *  from keyframe `from` to `to` and the current estimate `graph`:
   *  loop_max_discrepancy_m + loop_max_discrepancy_per_m x the estimated path
   *  length between them (consecutive nodes). */
  double loopDiscrepancyLimit(std::size_t from, std::size_t to, const TGraph& graph) const;

  /** The information matrix to put in the graph for a front-end measurement
   *  ([GraphSlam] edge_information). Constant-velocity constraints keep the
   *  front end's (deliberately weak) information. */
  frontend::TInformation66 edgeInformation(
      const frontend::TInformation66& frontEndInformation, frontend::ETrackingMethod method,
      std::size_t inliers,
      const frontend::TInformation66& estimatorInformation = frontend::TInformation66()) const;

  /** Squared Mahalanobis error of edge `it` against the graph's node poses
   *  in the residual SPA minimises (pseudo-log of inv(edge) (+) inv(P1) (+)
   *  P2). MRPT's getEdgeSquareError() measures (x y z yaw pitch roll) in the
   *  world frame instead, which disagrees with it whenever the information
   *  is not isotropic (and its SO(3) log is not used: NaN at zero error). */
  static double edgeChi2(const TGraph& graph, TGraph::edges_map_t::const_iterator it);

  /** Records an accepted closure (counted in loopClosures()). */
  void addLoopClosure(const TLoopClosure& lc) { m_loops.push_back(lc); }
  /** Accepted closures still in the graph. */
  const std::vector<TLoopClosure>& loopClosures() const { return m_loops; }
  /** Closures removed again by optimize() as outliers. */
  std::size_t rejectedLoopClosures() const { return m_rejectedLoops; }

  /** How much more the edges disagree than their information claims, as
   *  measured by the last whole-graph optimisation (graphVarianceFactor()),
   *  and never below 1: the chi-square tests (loop_outlier_chi2,
   *  optimize_min_chi2) are taken relative to it. 1 before any. */
  double varianceFactor() const { return m_varianceFactor; }
  /** The a-posteriori variance factor of an optimised graph, robustly: the
   *  median edge chi2 over what honest information gives an edge of the
   *  graph's mean redundancy (5.35, the median of chi2 with 6 degrees of
   *  freedom, times (6 edges - 6 (nodes - 1)) / (6 edges)); not below 1.
   *  The median keeps a few false closures from hiding themselves by
   *  inflating it. 1 when the graph has no redundancy. */
  static double graphVarianceFactor(const TGraph& graph);
  /** The factor the loop-outlier test uses: the larger of varianceFactor()
   *  and the closures' own (closureVarianceFactor() over the closures still
   *  in the graph), from the same optimisation. 1 before any. */
  double loopVarianceFactor() const { return m_loopVarianceFactor; }
  /** The closures' a-posteriori variance factor, robustly: their lower
   *  median chi2 over 5.348 (the median of chi2 with 6 degrees of freedom; a
   *  closure's redundancy is at most 1), not below 1; 1 with fewer than 3
   *  closures. Negative entries (closures no longer in the graph) are
   *  ignored. */
  static double closureVarianceFactor(std::vector<double> closureChi2);

  /** Optimises `graph` (SPA Levenberg-Marquardt, root fixed), removes loop
   *  edges that remain inconsistent (loop_outlier_chi2) and re-optimises.
   *  window > 0 (and smaller than the graph): only the newest `window` nodes
   *  move, and no closure is removed. The front end is not told: the caller
   *  hands the result on with correctFrontEnd(). measureChi2: the report's
   *  whole-graph chi2 before and after (a pass over every edge, 24 ms at 600
   *  keyframes on fr1/rpy there and back, growing with the graph: CKeyframeGSO
   *  asks for it only in the final optimisation, the one summary.json shows). */
  TOptimizationReport optimize(TGraph& graph, std::size_t window = 0, bool measureChi2 = true);
  /** The back end's one correction of the front end: every node pose of
   *  `graph` becomes its keyframe's pose (CRgbdOdometry::correctKeyframePoses). */
  void correctFrontEnd(const TGraph& graph);

  /** Keyframe map clouds in each keyframe's optical camera frame. */
  const std::vector<mrpt::maps::CColouredPointsMap>& keyframeClouds() const { return m_clouds; }

 private:
  TConfig m_config;
  EConfigOrigin m_origin = EConfigOrigin::Caller;
  std::unique_ptr<frontend::CRgbdOdometry> m_odometry;
  /** The landmark database, reached through the observation processor (the
   *  one path from a region to a landmark, as in roi-landmarks). */
  std::unique_ptr<landmarks::CObservationProcessor> m_landmarks;
  std::optional<frontend::TFrameResult> m_last;
  std::size_t m_framesRecorded = 0;
  std::vector<mrpt::maps::CColouredPointsMap> m_clouds;
  cv::Size m_imageSize;
  /** Keyframes already queried in the landmark database. */
  std::size_t m_landmarkQueried = 0;
  /** Landmark id -> keyframes that sighted it. */
  std::map<int32_t, std::vector<std::size_t>> m_sightings;
  std::vector<TLoopClosure> m_loops;
  std::size_t m_rejectedLoops = 0;
  double m_varianceFactor = 1;
  double m_loopVarianceFactor = 1;

  /** One round of optimize()'s closure test on an optimised graph: updates
   *  both variance factors and returns the indices (into m_loops, ascending)
   *  of the closures beyond loop_outlier_chi2 times loopVarianceFactor(). */
  std::vector<std::size_t> closureOutliers(const TGraph& graph);
};

/** "landmark" | "proximity". */
std::string toString(ELoopSource s);
/** `context`, else std::logic_error naming `decider`: one of our deciders
 *  made alone by MRPT's by-name factory has no context (those factories take
 *  no arguments, so cannot hand one context to several deciders);
 *  CRoislamOptionsChecker::createDeciders() makes them together. */
CSlamContext& sharedContext(const std::shared_ptr<CSlamContext>& context, const char* decider);
}  // namespace roislam::graphslam
