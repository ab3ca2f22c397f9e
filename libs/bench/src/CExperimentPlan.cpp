#include "roislam/bench/CExperimentPlan.h"

#include <mrpt/config/CConfigFileBase.h>
#include <roislam/bench/ProcessUtils.h>
#include <roislam/common/StringLists.h>
#include <roislam/io/SevenScenes.h>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace roislam::bench
{
using common::joinList;
using common::splitList;

namespace
{
std::string safeName(const std::string& s)
{
  std::string out = s;
  for (char& c : out)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '.')
      c = '_';
  return out;
}

/** A TUM folder, or a 7-Scenes sequence in that dataset's own layout. */
bool isSequence(const fs::path& p)
{
  return fs::is_regular_file(p / "rgb.txt") || io::isSevenScenesFolder(p.string());
}
}  // namespace

std::set<int> CExperimentPlan::parseTests(const std::string& text)
{
  std::set<int> tests;
  for (const auto& t : splitList(text))
  {
    if (t != "1" && t != "2" && t != "3" && t != "4")
      throw std::invalid_argument("tests: '" + t + "' is not one of 1, 2, 3, 4");
    tests.insert(std::stoi(t));
  }
  if (tests.empty())
    throw std::invalid_argument("tests: empty list");
  return tests;
}

void CExperimentPlan::TOptions::validate(const std::string& section) const
{
  const auto bad = [&](const std::string& key, const std::string& why)
  { return std::invalid_argument("[" + section + "] " + key + ": " + why); };
  for (int t : tests)
    if (t < 1 || t > 4)
      throw bad("tests", "values must be 1, 2, 3 or 4");
  const std::vector<std::string> knownF{"surf", "sift", "orb"};
  const std::vector<std::string> knownM{"traditional", "roi_small", "roi_big"};
  for (const auto& f : features)
    if (std::find(knownF.begin(), knownF.end(), f) == knownF.end())
      throw bad("features", "unknown extractor '" + f + "'");
  if (std::find(knownF.begin(), knownF.end(), test3_feature) == knownF.end())
    throw bad("test3_feature", "unknown extractor '" + test3_feature + "'");
  for (const auto& m : modes)
    if (std::find(knownM.begin(), knownM.end(), m) == knownM.end())
      throw bad("modes", "unknown mode '" + m + "'");
  for (const auto& m : test3_modes)
    if (std::find(knownM.begin(), knownM.end(), m) == knownM.end())
      throw bad("test3_modes", "unknown mode '" + m + "'");
  const std::vector<std::string> knownR{"rgbd", "icp", "rgbdicp"};
  for (const auto& m : reference_methods)
    if (std::find(knownR.begin(), knownR.end(), m) == knownR.end())
      throw bad("reference_methods", "unknown cv::rgbd odometry '" + m + "' (rgbd, icp, rgbdicp)");
  if (test1_max_features < 0)
    throw bad("test1_max_features", "must be >= 0");
  if (test2_max_features <= 0)
    throw bad("test2_max_features", "must be > 0");
  if (test3_max_features <= 0)
    throw bad("test3_max_features", "must be > 0");
  for (const auto* list : {&variants, &test1_variants})
  {
    std::set<std::string> names;
    for (const auto& v : *list)
      if (v.name.empty() || !names.insert(v.name).second)
        throw std::invalid_argument("variants: empty or repeated name '" + v.name + "'");
  }
}

void CExperimentPlan::TOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section)
{
  std::vector<std::string> testList;
  for (int t : tests)
    testList.push_back(std::to_string(t));
  const std::string testsText = cfg.read_string(section, "tests", joinList(testList));
  try
  {
    tests = parseTests(testsText);
  }
  catch (const std::invalid_argument& e)
  {
    throw std::invalid_argument("[" + section + "] " + e.what());
  }
  features = splitList(cfg.read_string(section, "features", joinList(features)));
  modes = splitList(cfg.read_string(section, "modes", joinList(modes)));
  test1_max_features = cfg.read_int(section, "test1_max_features", test1_max_features);
  test2_max_features = cfg.read_int(section, "test2_max_features", test2_max_features);
  test3_max_features = cfg.read_int(section, "test3_max_features", test3_max_features);
  test3_feature = cfg.read_string(section, "test3_feature", test3_feature);
  test3_modes = splitList(cfg.read_string(section, "test3_modes", joinList(test3_modes)));
  snapshots = cfg.read_bool(section, "snapshots", snapshots);
  reference_methods = parseReferenceMethods(
      cfg.read_string(section, "reference_methods", joinList(reference_methods)));
  validate(section);
}

void CExperimentPlan::TOptions::saveToConfigFile(
    mrpt::config::CConfigFileBase& cfg, const std::string& section) const
{
  std::vector<std::string> testList;
  for (int t : tests)
    testList.push_back(std::to_string(t));
  cfg.write(section, "tests", joinList(testList));
  cfg.write(section, "features", joinList(features));
  cfg.write(section, "modes", joinList(modes));
  cfg.write(section, "test1_max_features", test1_max_features);
  cfg.write(section, "test2_max_features", test2_max_features);
  cfg.write(section, "test3_max_features", test3_max_features);
  cfg.write(section, "test3_feature", test3_feature);
  cfg.write(section, "test3_modes", joinList(test3_modes));
  cfg.write(section, "snapshots", snapshots);
  cfg.write(
      section, "reference_methods",
      reference_methods.empty() ? std::string("none") : joinList(reference_methods));
}

std::vector<std::string> CExperimentPlan::parseReferenceMethods(const std::string& text)
{
  auto list = splitList(text);
  if (list.size() == 1 && list[0] == "none")
    list.clear();
  return list;
}

CExperimentPlan::CExperimentPlan(const TOptions& options, const TLocations& locations)
    : m_options(options), m_locations(locations)
{
  m_options.validate();
}

TBenchRun CExperimentPlan::makeRun(
    int test, const TSequence& seq, const std::string& mode, const std::string& feature,
    int maxFeatures, const TVariant* variant) const
{
  TBenchRun r;
  r.test = test;
  r.sequence = seq.name;
  r.sequencePath = seq.path;
  r.app = test == 1 ? "roi-landmarks" : "roi-graphslam";
  r.mode = mode;
  r.feature = feature;
  r.maxFeatures = maxFeatures;
  r.id = "t" + std::to_string(test) + "-" + safeName(seq.name);
  if (!mode.empty())
    r.id += "-" + mode;
  r.id += "-" + feature;
  if (maxFeatures > 0)
    r.id += "-" + std::to_string(maxFeatures);
  const fs::path cfgDir(m_locations.configDir);
  const std::string config = test == 1 ? "roi_landmarks" : mode;
  r.baseIni = (cfgDir / (config + ".ini")).string();
  r.iniFile = r.baseIni;
  if (variant)
  {
    r.variant = variant->name;
    r.variantLabel = variant->label;
    r.id += "-" + variant->name;
    r.iniOverrides = variant->overrides;
    r.iniFile =
        (fs::path(m_locations.outputDir) / "configs" / (config + "-" + variant->name + ".ini"))
            .string();
  }
  placeRun(r);
  if (test != 1)
    r.argv.insert(r.argv.end(), {"--mode", mode});
  r.argv.insert(r.argv.end(), {"--feature", feature});
  if (maxFeatures > 0)
    r.argv.insert(r.argv.end(), {"--max-features", std::to_string(maxFeatures)});
  if (test != 1 && !m_options.snapshots)
    r.argv.push_back("--no-snapshot");
  return r;
}

void CExperimentPlan::placeRun(TBenchRun& r) const
{
  r.runDir = (fs::path(m_locations.outputDir) / "runs" / r.id).string();
  r.appOutputDir = (fs::path(r.runDir) / "output").string();
  const auto exe = m_locations.executables.find(r.app);
  r.argv = {
      exe != m_locations.executables.end() ? exe->second : r.app,
      "--ini",
      r.iniFile,
      "--input",
      r.sequencePath,
      "--output-dir",
      r.appOutputDir};
}

TBenchRun CExperimentPlan::makeTest4Run(
    const TSequence& seq, const std::string& kind, const std::string& feature) const
{
  TBenchRun r;
  r.test = 4;
  r.sequence = seq.name;
  r.sequencePath = seq.path;
  r.feature = feature;
  const bool ekf = kind == "kf_slam";
  r.app = ekf ? "roi-landmarks" : "roi-graphslam";
  r.mode = kind;
  r.id = "t4-" + safeName(seq.name) + "-" + kind + "-" + feature;
  r.baseIni =
      (fs::path(m_locations.configDir) / (ekf ? "roi_landmarks.ini" : "roi_big.ini")).string();
  r.iniFile = r.baseIni;
  placeRun(r);
  if (ekf)
    r.argv.push_back("--kf-slam");
  else
    r.argv.insert(r.argv.end(), {"--mode", "roi_big"});
  r.argv.insert(r.argv.end(), {"--feature", feature});
  if (!ekf && !m_options.snapshots)
    r.argv.push_back("--no-snapshot");
  return r;
}

TBenchRun CExperimentPlan::makeReferenceRun(const TSequence& seq, const std::string& method) const
{
  TBenchRun r;
  r.test = 0;
  r.sequence = seq.name;
  r.sequencePath = seq.path;
  r.app = "cv-odometry";
  r.mode = "cv_" + method;
  r.id = "ref-" + safeName(seq.name) + "-" + r.mode;
  placeRun(r);
  // cv-odometry has no mode config: its options are OpenCV's defaults.
  r.argv = {r.argv[0],      "--input",  r.sequencePath, "--output-dir",
            r.appOutputDir, "--method", method};
  return r;
}

std::vector<TBenchRun> CExperimentPlan::build(const std::vector<TSequence>& sequences) const
{
  std::vector<TBenchRun> runs;
  const auto addSlam =
      [&](int test, const TSequence& s, const std::string& mode, const std::string& f, int cap)
  {
    if (mode == "traditional" || m_options.variants.empty())
      runs.push_back(makeRun(test, s, mode, f, cap, nullptr));
    else
      for (const auto& v : m_options.variants)
        runs.push_back(makeRun(test, s, mode, f, cap, &v));
  };
  if (m_options.tests.count(1))
    for (const auto& s : sequences)
      for (const auto& f : m_options.features)
      {
        runs.push_back(makeRun(1, s, "", f, m_options.test1_max_features, nullptr));
        for (const auto& v : m_options.test1_variants)
          runs.push_back(makeRun(1, s, "", f, m_options.test1_max_features, &v));
      }
  if (m_options.tests.count(2))
    for (const auto& s : sequences)
      for (const auto& m : m_options.modes)
        for (const auto& f : m_options.features)
          addSlam(2, s, m, f, m_options.test2_max_features);
  if (m_options.tests.count(3))
    for (const auto& s : sequences)
      for (const auto& m : m_options.test3_modes)
        addSlam(3, s, m, m_options.test3_feature, m_options.test3_max_features);
  if (m_options.tests.count(4))
    for (const auto& s : sequences)
      for (const auto& f : m_options.features)
        for (const std::string kind : {"kf_slam", "graph_slam"})
          runs.push_back(makeTest4Run(s, kind, f));
  for (const auto& s : sequences)
    for (const auto& m : m_options.reference_methods)
      runs.push_back(makeReferenceRun(s, m));
  return runs;
}

void CExperimentPlan::writeVariantConfigs(const std::vector<TBenchRun>& runs)
{
  std::set<std::string> written;
  for (const auto& r : runs)
  {
    if (r.iniOverrides.empty() || r.iniFile == r.baseIni || !written.insert(r.iniFile).second)
      continue;
    const std::string base = readFile(r.baseIni);
    fs::create_directories(fs::path(r.iniFile).parent_path());
    writeFileAtomically(
        r.iniFile, "; written by roi-bench from " + r.baseIni + " (variant " + r.variant + ")\n" +
                       applyIniOverrides(base, r.iniOverrides));
  }
}

std::vector<TSequence> CExperimentPlan::discoverSequences(const std::vector<std::string>& dirs)
{
  std::vector<TSequence> out;
  std::set<std::string> names;
  const auto add = [&](const fs::path& p)
  {
    TSequence s;
    s.path = fs::absolute(p).lexically_normal().string();
    if (!s.path.empty() && s.path.back() == '/')
      s.path.pop_back();
    std::string base = fs::path(s.path).filename().string();
    // 7-Scenes names its sequences seq-01, seq-02, ... in every scene.
    const bool sevenScenes = io::isSevenScenesFolder(s.path);
    if (sevenScenes)
      base = fs::path(s.path).parent_path().filename().string() + "_" + base;
    s.name = base;
    for (int k = 2; names.count(s.name); ++k)
      s.name = base + "_" + std::to_string(k);
    names.insert(s.name);
    s.hasGroundTruth = fs::is_regular_file(p / "groundtruth.txt") ||
                       (sevenScenes && fs::is_regular_file(p / "frame-000000.pose.txt"));
    out.push_back(s);
  };
  for (const auto& d : dirs)
  {
    const fs::path p(d);
    if (isSequence(p))
    {
      add(p);
      continue;
    }
    std::vector<fs::path> subs;
    if (fs::is_directory(p))
      for (const auto& e : fs::directory_iterator(p))
        if (e.is_directory() && isSequence(e.path()))
          subs.push_back(e.path());
    if (subs.empty())
      throw std::runtime_error(d + ": no sequence (a folder with rgb.txt) found there");
    std::sort(subs.begin(), subs.end());
    for (const auto& s : subs)
      add(s);
  }
  return out;
}
}  // namespace roislam::bench
