/* The two ini layouts of the SLAM configuration (CSlamContext::TConfig) and
 * which decider's loadParams() reads which part of it.
 *
 * roi-graphslam's layout: [FrontEnd] (the front end, TRgbdOdometryOptions.h) and
 * [GraphSlam] (the back end, CSlamContext.h). MRPT graphslam-engine's layout
 * (roi-graphslam-engine, config/graphslam-engine.ini): the same keys in
 * MRPT's sections, by the class that reads them:
 *  - [NodeRegistrationDeciderParameters]  CKeyframeNRD: every [FrontEnd] key
 *  - [GeneralConfiguration]  CKeyframeNRD / CKeyframeERD: the graph's edge
 *      weights (edge_information, edge_sigma_m, edge_sigma_deg) and the map
 *      (map_decimation, map_max_depth_m), next to MRPT's own keys
 *  - [EdgeRegistrationDeciderParameters]  CKeyframeERD: loop_min_keyframe_gap,
 *      landmark_loops, proximity_loops, proximity_radius_m,
 *      proximity_max_angle_deg, max_loop_candidates, loop_min_inliers,
 *      loop_max_discrepancy_m, loop_max_discrepancy_per_m
 *  - [OptimizerParameters]  CKeyframeGSO: optimizer_max_iterations,
 *      loop_outlier_chi2, optimize_min_chi2, optimize_every_keyframes,
 *      optimize_window_keyframes, next to CLevMarqGSO's own keys
 * Both layouts share the components' sections: [RoiDetector],
 * [FeatureExtractor], [FeatureMatcher] (read with the front end, so by
 * CKeyframeNRD), [LandmarkDatabase], [HomographyLocator] (CKeyframeERD).
 *
 * An ini uses roi-graphslam's layout when it has [FrontEnd] or [GraphSlam],
 * else MRPT's (so an ini without any of these sections runs on the defaults).
 * Keys MRPT's engine or its own deciders read in these sections are accepted
 * (class_verbosity everywhere; [GeneralConfiguration] output and ground-truth
 * keys; CLevMarqGSO's [OptimizerParameters] keys); any other key is an error.
 */
#pragma once

#include <mrpt/config/CConfigFileBase.h>
#include <roislam/graphslam/CSlamContext.h>

#include <string>
#include <vector>

namespace roislam::graphslam
{
/** The parts of the configuration, by the decider whose loadParams() reads it. */
enum class ESlamParams
{
  NodeRegistration,  //!< CKeyframeNRD: front end and its components, map, edge weights
  EdgeRegistration,  //!< CKeyframeERD: loop closures, landmark database, edge weights
  Optimizer          //!< CKeyframeGSO: optimisation schedule
};

enum class ESlamIniLayout
{
  RoiGraphSlam,    //!< [FrontEnd], [GraphSlam]
  GraphSlamEngine  //!< MRPT's [GeneralConfiguration], [...DeciderParameters], [OptimizerParameters]
};

/** The layout of `cfg` (see above). Throws std::runtime_error "ini <fileLabel>:
 *  [Section] key: ..." when an ini in roi-graphslam's layout also sets one of
 *  our keys in an MRPT section (which would be silently ignored). */
ESlamIniLayout slamIniLayout(
    const mrpt::config::CConfigFileBase& cfg, const std::string& fileLabel);

/** Reads the sections of `part` in the ini's layout into `config` (keys
 *  absent keep their values; other parts are untouched). Throws
 *  std::runtime_error "ini <fileLabel>: [Section] unknown key 'x'" for a key
 *  nobody reads and "ini <fileLabel>: [Section] key: why" for a bad value. */
void loadSlamParams(
    const mrpt::config::CConfigFileBase& cfg, const std::string& fileLabel, ESlamParams part,
    CSlamContext::TConfig& config);

/** Every value of `config` into `out`, in roi-graphslam's layout ([FrontEnd],
 *  [GraphSlam], [LandmarkDatabase], [HomographyLocator]). */
void saveSlamConfig(const CSlamContext::TConfig& config, mrpt::config::CConfigFileBase& out);

/** The values of `part` in `config` as ini text in `layout`: "[Section]"
 *  lines, then "key = value", with "  (default)" after the keys `ini` does
 *  not set (no marks when `ini` is null). For the deciders' printParams() and
 *  getDescriptiveReport(). */
std::string describeSlamParams(
    const CSlamContext::TConfig& config, ESlamParams part, ESlamIniLayout layout,
    const mrpt::config::CConfigFileBase* ini);

/** What our deciders' loadParams(iniFile) do with their part: when the
 *  context's configuration comes from the deciders
 *  (CSlamContext::EConfigOrigin::DecidersLoadParams), reads `part` from
 *  `iniFile` into it (CSlamContext::configure()). Returns the parameters in
 *  use as printParams() shows them, headed by `decider` and where they came
 *  from. Throws "ini <file>: cannot open" and loadSlamParams()'s errors. */
std::string loadDeciderParams(
    CSlamContext& context, const std::string& iniFile, ESlamParams part,
    const std::string& decider);

/** The MRPT section of each [GraphSlam] key in MRPT's layout (every key of
 *  CSlamContext::TOptions is in exactly one; checked by a test). */
std::vector<std::pair<std::string, std::vector<std::string>>> engineGraphSlamSections();
}  // namespace roislam::graphslam
