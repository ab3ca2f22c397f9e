#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/system/filesystem.h>
#include <mrpt/system/string_utils.h>
#include <roislam/common/CStrictIniFile.h>
#include <roislam/common/IniKeyCheck.h>
#include <roislam/graphslam/SlamIni.h>

#include <algorithm>
#include <sstream>
#include <stdexcept>

namespace roislam::graphslam
{
namespace
{
const char* kGeneral = "GeneralConfiguration";
const char* kNode = "NodeRegistrationDeciderParameters";
const char* kEdge = "EdgeRegistrationDeciderParameters";
const char* kOptimizer = "OptimizerParameters";

using TKeys = std::vector<std::string>;

const TKeys kEdgeWeightKeys{"edge_information", "edge_sigma_m", "edge_sigma_deg"};
const TKeys kMapKeys{"map_decimation", "map_max_depth_m"};
const TKeys kLoopKeys{
    "loop_min_keyframe_gap", "landmark_loops",          "proximity_loops",
    "proximity_radius_m",    "proximity_max_angle_deg", "max_loop_candidates",
    "loop_min_inliers",      "loop_max_discrepancy_m",  "loop_max_discrepancy_per_m"};
const TKeys kOptimizerKeys{
    "optimizer_max_iterations", "loop_outlier_chi2", "optimize_min_chi2",
    "optimize_every_keyframes", "optimize_window_keyframes"};

/** Keys MRPT 2.5's engine, CGraphSlamHandler and CLevMarqGSO read in these
 *  sections: accepted, not ours. */
const TKeys kMrptGeneralKeys{
    "class_verbosity",
    "user_decides_about_output_dir",
    "ground_truth_file_format",
    "output_dir_fname",
    "save_graph",
    "save_3DScene",
    "save_map",
    "save_graph_fname",
    "save_3DScene_fname",
    "save_map_fname",
    "LC_min_nodeid_diff"};
const TKeys kMrptDeciderKeys{"class_verbosity"};
const TKeys kMrptOptimizerKeys{
    "class_verbosity",
    "optimization_on_second_thread",
    "optimization_distance",
    "verbose",
    "profiler",
    "max_iterations",
    "tau",
    "max_used_consecutive_loop_closures",
    "max_ignored_consecutive_loop_closures"};

TKeys join(std::initializer_list<const TKeys*> lists)
{
  TKeys out;
  for (const auto* l : lists)
    out.insert(out.end(), l->begin(), l->end());
  return out;
}

bool contains(const TKeys& keys, const std::string& key)
{
  return std::any_of(
      keys.begin(), keys.end(),
      [&](const std::string& k) { return mrpt::system::strCmpI(k, key); });
}

/** One section of a part, as the ini names it. */
struct TSection
{
  std::string name;
  /** Where the options save these keys (CLoadableOptions layout): FrontEnd,
   *  its component sections, GraphSlam, LandmarkDatabase, HomographyLocator. */
  std::string source;
  /** Our keys shown for this part; empty: all of `source`. */
  TKeys shown;
  /** Every key that may appear in the section (empty: `shown`, or all of
   *  `source`). */
  TKeys allowed;
};

/** The keys the options save under `source`. */
TKeys sourceKeys(const CSlamContext::TConfig& defaults, const std::string& source)
{
  if (source == "GraphSlam")
    return common::knownIniKeys(defaults.backEnd, "GraphSlam");
  if (source == "LandmarkDatabase")
    return common::knownIniKeys(defaults.database, "LandmarkDatabase");
  if (source == "HomographyLocator")
    return common::knownIniKeys(defaults.locator, "HomographyLocator");
  // The front end saves its components under their fixed section names.
  return common::knownIniKeys(defaults.frontEnd, "FrontEnd", source);
}

std::vector<TSection> sections(ESlamParams part, ESlamIniLayout layout)
{
  const bool engine = layout == ESlamIniLayout::GraphSlamEngine;
  const CSlamContext::TConfig d;
  const TKeys frontEnd = sourceKeys(d, "FrontEnd");
  const TKeys general = join({&kEdgeWeightKeys, &kMapKeys});
  const TKeys allGraphSlam = sourceKeys(d, "GraphSlam");
  std::vector<TSection> out;
  switch (part)
  {
    case ESlamParams::NodeRegistration:
      out.push_back(
          engine ? TSection{kNode, "FrontEnd", {}, join({&frontEnd, &kMrptDeciderKeys})}
                 : TSection{"FrontEnd", "FrontEnd", {}, {}});
      for (const char* s : {"RoiDetector", "FeatureExtractor", "FeatureMatcher"})
        out.push_back({s, s, {}, {}});
      out.push_back(
          engine ? TSection{kGeneral, "GraphSlam", general, join({&general, &kMrptGeneralKeys})}
                 : TSection{"GraphSlam", "GraphSlam", general, allGraphSlam});
      break;
    case ESlamParams::EdgeRegistration:
      if (engine)
      {
        out.push_back({kEdge, "GraphSlam", kLoopKeys, join({&kLoopKeys, &kMrptDeciderKeys})});
        out.push_back(
            {kGeneral, "GraphSlam", kEdgeWeightKeys, join({&general, &kMrptGeneralKeys})});
      }
      else
        out.push_back(
            {"GraphSlam", "GraphSlam", join({&kLoopKeys, &kEdgeWeightKeys}), allGraphSlam});
      for (const char* s : {"LandmarkDatabase", "HomographyLocator"})
        out.push_back({s, s, {}, {}});
      break;
    case ESlamParams::Optimizer:
      out.push_back(
          engine
              ? TSection{kOptimizer, "GraphSlam", kOptimizerKeys, join({&kOptimizerKeys, &kMrptOptimizerKeys})}
              : TSection{"GraphSlam", "GraphSlam", kOptimizerKeys, allGraphSlam});
      break;
  }
  for (auto& s : out)
    if (s.allowed.empty())
      s.allowed = s.shown.empty() ? sourceKeys(d, s.source) : s.shown;
  return out;
}

/** Reads one section into the options that own its keys. */
void loadSection(
    const mrpt::config::CConfigFileBase& cfg, const TSection& s, CSlamContext::TConfig& config)
{
  if (s.source == "FrontEnd")
    config.frontEnd.loadFromConfigFile(cfg, s.name);  // with its component sections
  else if (s.source == "GraphSlam")
    config.backEnd.loadFromConfigFile(cfg, s.name);
  else if (s.source == "LandmarkDatabase")
    config.database.loadFromConfigFile(cfg, s.name);
  else if (s.source == "HomographyLocator")
    config.locator.loadFromConfigFile(cfg, s.name);
}
}  // namespace

std::vector<std::pair<std::string, std::vector<std::string>>> engineGraphSlamSections()
{
  return {
      {kGeneral, join({&kEdgeWeightKeys, &kMapKeys})},
      {kEdge, kLoopKeys},
      {kOptimizer, kOptimizerKeys}};
}

ESlamIniLayout slamIniLayout(const mrpt::config::CConfigFileBase& cfg, const std::string& fileLabel)
{
  if (!cfg.sectionExists("FrontEnd") && !cfg.sectionExists("GraphSlam"))
    return ESlamIniLayout::GraphSlamEngine;
  // roi-graphslam's layout: our keys in MRPT's sections would be ignored.
  const CSlamContext::TConfig d;
  const TKeys frontEnd = sourceKeys(d, "FrontEnd"), graphSlam = sourceKeys(d, "GraphSlam");
  const TKeys ours = join({&frontEnd, &graphSlam});
  for (const char* section : {kGeneral, kNode, kEdge, kOptimizer})
  {
    if (!cfg.sectionExists(section))
      continue;
    std::vector<std::string> present;
    cfg.getAllKeys(section, present);
    for (const auto& key : present)
      if (contains(ours, key))
        throw std::runtime_error(
            "ini " + fileLabel + ": [" + section + "] " + key +
            ": this ini uses roi-graphslam's sections ([FrontEnd], [GraphSlam]); set it there, "
            "or use MRPT's sections only");
  }
  return ESlamIniLayout::RoiGraphSlam;
}

void loadSlamParams(
    const mrpt::config::CConfigFileBase& cfg, const std::string& fileLabel, ESlamParams part,
    CSlamContext::TConfig& config)
{
  const auto all = sections(part, slamIniLayout(cfg, fileLabel));
  for (const auto& s : all)
    common::checkIniKeys(cfg, s.name, s.allowed, fileLabel);
  try
  {
    for (const auto& s : all)
      loadSection(cfg, s, config);
  }
  catch (const std::exception& e)
  {
    std::string what = e.what();
    throw std::runtime_error("ini " + fileLabel + ": " + what.substr(0, what.find('\n')));
  }
}

void saveSlamConfig(const CSlamContext::TConfig& config, mrpt::config::CConfigFileBase& out)
{
  config.frontEnd.saveToConfigFile(out, "FrontEnd");
  config.backEnd.saveToConfigFile(out, "GraphSlam");
  config.database.saveToConfigFile(out, "LandmarkDatabase");
  config.locator.saveToConfigFile(out, "HomographyLocator");
}

std::string describeSlamParams(
    const CSlamContext::TConfig& config, ESlamParams part, ESlamIniLayout layout,
    const mrpt::config::CConfigFileBase* ini)
{
  mrpt::config::CConfigFileMemory values;
  saveSlamConfig(config, values);
  std::ostringstream ss;
  for (const auto& s : sections(part, layout))
  {
    ss << "[" << s.name << "]\n";
    TKeys keys = s.shown;
    if (keys.empty())
      values.getAllKeys(s.source, keys);
    std::vector<std::string> set;
    if (ini && ini->sectionExists(s.name))
      ini->getAllKeys(s.name, set);
    for (const auto& key : keys)
    {
      ss << key << " = " << values.read_string(s.source, key, "");
      if (ini && !contains(set, key))
        ss << "  (default)";
      ss << "\n";
    }
  }
  return ss.str();
}

std::string loadDeciderParams(
    CSlamContext& context, const std::string& iniFile, ESlamParams part, const std::string& decider)
{
  if (context.configOrigin() == CSlamContext::EConfigOrigin::Caller || iniFile.empty())
    return decider + " parameters (" +
           (context.configOrigin() == CSlamContext::EConfigOrigin::Caller ? "given by the caller"
                                                                          : "no ini: defaults") +
           "):\n" +
           describeSlamParams(context.config(), part, ESlamIniLayout::RoiGraphSlam, nullptr);
  // Strict syntax (file:line errors) before MRPT's reader sees the keys.
  const common::CStrictIniFile cfg(iniFile);
  const ESlamIniLayout layout = slamIniLayout(cfg, iniFile);
  CSlamContext::TConfig config = context.config();
  loadSlamParams(cfg, iniFile, part, config);
  context.configure(config);
  return decider + " parameters (ini " + iniFile + ", " +
         (layout == ESlamIniLayout::GraphSlamEngine ? "MRPT's sections"
                                                    : "roi-graphslam's sections") +
         "; (default): not set there):\n" + describeSlamParams(config, part, layout, &cfg);
}
}  // namespace roislam::graphslam
