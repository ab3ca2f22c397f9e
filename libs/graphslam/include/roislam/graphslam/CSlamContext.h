/* State shared by our node and edge registration deciders (CKeyframeNRD,
 * CKeyframeERD) and the optimiser (CKeyframeGSO): the front end
 * (CRgbdOdometry: one graph node per keyframe, node id == keyframe id), the
 * ROI landmark database used for loop-closure candidates, per-keyframe map
 * clouds, and the loop-closure bookkeeping. MRPT's engine gives each decider
 * only the graph, so the deciders hold a shared_ptr to one context. Created by
 * CRoiGraphSlamApp (or a test) and handed to the deciders with setContext().
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
 *                              this is removed as a false closure and the
 *                              graph re-optimised (at most 3 rounds)
 *  - optimize_min_chi2         double >= 0 (30, as loop_outlier_chi2): a
 *                              keyframe whose new loop closure disagrees with
 *                              the current estimate by more (squared
 *                              Mahalanobis error) is optimised at once;
 *                              0 = at every loop closure
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
 *  - edge_information          frontend|diagonal (diagonal): edge weights as
 *                              the front end computes them (reprojection
 *                              Hessian, very confident: sigma ~0.3 mm), or
 *                              diagonal from the two sigmas below, scaled by
 *                              sqrt(100 / inliers) (10..1000 inliers)
 *  - edge_sigma_m              [m] > 0 (0.01): translation sigma at 100 inliers
 *  - edge_sigma_deg            [deg] > 0 (0.5): rotation sigma at 100 inliers
 * A bad value throws std::invalid_argument "[GraphSlam] key: why".
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
};

/** Summary of one graph optimisation. */
struct TOptimizationReport
{
  std::size_t iterations = 0;
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
    std::string edge_information = "diagonal";
    double edge_sigma_m = 0.01;
    double edge_sigma_deg = 0.5;

    void loadFromConfigFile(
        const mrpt::config::CConfigFileBase& source, const std::string& section) override;
    void saveToConfigFile(
        mrpt::config::CConfigFileBase& target, const std::string& section) const override;
    /** Throws std::invalid_argument "[GraphSlam] key: why". */
    void validate() const;
  };

  /** Everything the context is built from. */
  struct TConfig
  {
    TOptions backEnd;                                 // [GraphSlam]
    frontend::CRgbdOdometry::TOptions frontEnd;       // [FrontEnd] + sub-sections
    landmarks::CLandmarkDatabase::TOptions database;  // [LandmarkDatabase]
    matching::CHomographyLocator::TOptions locator;   // [HomographyLocator]
  };

  CSlamContext();
  explicit CSlamContext(const TConfig& config);

  /** Reads every section of `cfg` (absent sections keep defaults) after
   *  checking that [GraphSlam], [FrontEnd], [RoiDetector], [FeatureExtractor],
   *  [FeatureMatcher], [LandmarkDatabase] and [HomographyLocator] hold only
   *  known keys: "ini <fileLabel>: [Section] unknown key 'x'". */
  static TConfig loadConfig(const mrpt::config::CConfigFileBase& cfg, const std::string& fileLabel);

  /** The context shared by the deciders of one graph when they were created
   *  by name (TUserOptionsChecker factories have no arguments): created with
   *  default options on first use; setForGraph() replaces it (e.g. from the
   *  ini given to loadParams()). */
  static std::shared_ptr<CSlamContext> forGraph(const void* graph);
  static void setForGraph(const void* graph, std::shared_ptr<CSlamContext> context);

  frontend::CRgbdOdometry& odometry() { return m_odometry; }
  const frontend::CRgbdOdometry& odometry() const { return m_odometry; }
  const landmarks::CLandmarkDatabase& database() const { return m_landmarks.tracker().database(); }
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

  /** The information matrix to put in the graph for a front-end measurement
   *  ([GraphSlam] edge_information). Constant-velocity constraints keep the
   *  front end's (deliberately weak) information. */
  /** Largest translation discrepancy accepted between a verified closure
   *  from keyframe `from` to `to` and the current estimate `graph`:
   *  loop_max_discrepancy_m + loop_max_discrepancy_per_m x the estimated path
   *  length between them (consecutive nodes). */
  double loopDiscrepancyLimit(std::size_t from, std::size_t to, const TGraph& graph) const;

  frontend::TInformation66 edgeInformation(
      const frontend::TInformation66& frontEndInformation, frontend::ETrackingMethod method,
      std::size_t inliers) const;

  /** Records an accepted closure (counted in loopClosures()). */
  void addLoopClosure(const TLoopClosure& lc) { m_loops.push_back(lc); }
  /** Accepted closures still in the graph. */
  const std::vector<TLoopClosure>& loopClosures() const { return m_loops; }
  /** Closures removed again by optimize() as outliers. */
  std::size_t rejectedLoopClosures() const { return m_rejectedLoops; }

  /** Optimises `graph` (SPA Levenberg-Marquardt, root fixed), removes loop
   *  edges that remain inconsistent (loop_outlier_chi2) and re-optimises.
   *  window > 0 (and smaller than the graph): only the newest `window` nodes
   *  move, and no closure is removed. The front end is not told: the caller
   *  hands the result on with correctFrontEnd(). */
  TOptimizationReport optimize(TGraph& graph, std::size_t window = 0);
  /** The back end's one correction of the front end: every node pose of
   *  `graph` becomes its keyframe's pose (CRgbdOdometry::correctKeyframePoses). */
  void correctFrontEnd(const TGraph& graph);

  /** Keyframe map clouds in each keyframe's optical camera frame. */
  const std::vector<mrpt::maps::CColouredPointsMap>& keyframeClouds() const { return m_clouds; }

 private:
  TConfig m_config;
  frontend::CRgbdOdometry m_odometry;
  /** The landmark database, reached through the observation processor (the
   *  one path from a region to a landmark, as in roi-landmarks). */
  landmarks::CObservationProcessor m_landmarks;
  std::optional<frontend::TFrameResult> m_last;
  std::vector<mrpt::maps::CColouredPointsMap> m_clouds;
  cv::Size m_imageSize;
  /** Keyframes already queried in the landmark database. */
  std::size_t m_landmarkQueried = 0;
  /** Landmark id -> keyframes that sighted it. */
  std::map<int32_t, std::vector<std::size_t>> m_sightings;
  std::vector<TLoopClosure> m_loops;
  std::size_t m_rejectedLoops = 0;
};

/** "landmark" | "proximity". */
std::string toString(ELoopSource s);
}  // namespace roislam::graphslam
