/* The SLAM configuration in MRPT's graph-SLAM sections (SlamIni.h): the
 * shipped config/graphslam-engine.ini is config/roi_big.ini in the other
 * layout; every back-end key lives in exactly one MRPT section; the
 * deciders made by name read their parts with loadParams() and print them
 * with printParams(), marking defaults; bad values and misplaced keys name
 * the section the user wrote. */
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <roislam/common/IniKeyCheck.h>
#include <roislam/graphslam/CKeyframeERD.h>
#include <roislam/graphslam/CKeyframeGSO.h>
#include <roislam/graphslam/CKeyframeNRD.h>
#include <roislam/graphslam/CRoislamOptionsChecker.h>
#include <roislam/graphslam/SensorFacts.h>
#include <roislam/graphslam/SlamIni.h>
#include <roislam/testing/TestData.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>

namespace graphslam = roislam::graphslam;

namespace
{
std::string config(const std::string& name)
{
  return roislam::testing::sourceDir() + "/config/" + name;
}

/** Every value of a configuration, as ini text. */
std::string dump(const graphslam::CSlamContext::TConfig& c)
{
  mrpt::config::CConfigFileMemory m;
  graphslam::saveSlamConfig(c, m);
  std::string text;
  m.getContent(text);
  return text;
}

std::string loadError(const std::string& text)
{
  mrpt::config::CConfigFileMemory ini(text);
  try
  {
    graphslam::CSlamContext::loadConfig(ini, "t.ini");
  }
  catch (const std::exception& e)
  {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(SlamIni, ShippedEngineIniIsRoiBigInMrptsSections)
{
  const std::string engine = config("graphslam-engine.ini"), roiBig = config("roi_big.ini");
  const mrpt::config::CConfigFile e(engine), r(roiBig);
  EXPECT_EQ(graphslam::slamIniLayout(e, engine), graphslam::ESlamIniLayout::GraphSlamEngine);
  EXPECT_EQ(graphslam::slamIniLayout(r, roiBig), graphslam::ESlamIniLayout::RoiGraphSlam);
  // Both apps take the camera facts (rolling-shutter readout, depth noise)
  // from the sensor description at run time (SensorFacts.h): neither ini
  // sets them, so the two configurations are the same to the last key.
  EXPECT_FALSE(graphslam::iniSetsReadout(e, engine));
  EXPECT_FALSE(graphslam::iniSetsReadout(r, roiBig));
  const auto engineConfig = graphslam::CSlamContext::loadConfig(e, engine);
  const auto roiBigConfig = graphslam::CSlamContext::loadConfig(r, roiBig);
  EXPECT_EQ(dump(engineConfig), dump(roiBigConfig));
}

// config/graphslam-engine.ini documents every key our deciders read: each
// one they print (describeSlamParams) is in its section there, set or
// commented out on its default, with a comment line above it.
TEST(SlamIni, ShippedEngineIniDocumentsEveryKey)
{
  std::ifstream in(config("graphslam-engine.ini"));
  std::map<std::string, std::set<std::string>> documented;  // section -> keys
  std::string line, section, previous;
  while (std::getline(in, line))
  {
    if (!line.empty() && line.front() == '[')
      section = line.substr(1, line.find(']') - 1);
    const std::string body = line.rfind("# ", 0) == 0 ? line.substr(2) : line;
    const auto eq = body.find(" = ");
    if (eq != std::string::npos && body.find(' ') == eq && previous.rfind("#", 0) == 0)
      documented[section].insert(body.substr(0, eq));
    previous = line;
  }
  const graphslam::CSlamContext::TConfig defaults;
  std::size_t keys = 0;
  for (const auto part :
       {graphslam::ESlamParams::NodeRegistration, graphslam::ESlamParams::EdgeRegistration,
        graphslam::ESlamParams::Optimizer})
  {
    std::istringstream printed(graphslam::describeSlamParams(
        defaults, part, graphslam::ESlamIniLayout::GraphSlamEngine, nullptr));
    while (std::getline(printed, line))
    {
      if (!line.empty() && line.front() == '[')
      {
        section = line.substr(1, line.find(']') - 1);
        continue;
      }
      const std::string key = line.substr(0, line.find(" = "));
      EXPECT_TRUE(documented[section].count(key)) << "[" << section << "] " << key;
      ++keys;
    }
  }
  EXPECT_GT(keys, 80u);
}

TEST(SlamIni, EveryBackEndKeyInExactlyOneMrptSection)
{
  const auto all = roislam::common::knownIniKeys(graphslam::CSlamContext::TOptions(), "GraphSlam");
  std::multiset<std::string> placed;
  for (const auto& [section, keys] : graphslam::engineGraphSlamSections())
    placed.insert(keys.begin(), keys.end());
  EXPECT_EQ(placed.size(), all.size());
  for (const auto& key : all)
    EXPECT_EQ(placed.count(key), 1u) << key;
}

TEST(SlamIni, BadValuesAndMisplacedKeysNameTheSection)
{
  EXPECT_NE(
      loadError("[OptimizerParameters]\noptimize_every_keyframes = 0\n")
          .find("ini t.ini: [OptimizerParameters] optimize_every_keyframes: must be >= 1"),
      std::string::npos);
  EXPECT_NE(
      loadError("[GeneralConfiguration]\nedge_information = isotropic\n")
          .find("[GeneralConfiguration] edge_information: unknown value 'isotropic'"),
      std::string::npos);
  EXPECT_NE(
      loadError("[NodeRegistrationDeciderParameters]\nmin_inliers = 1\n")
          .find("[NodeRegistrationDeciderParameters] min_inliers: must be >= 3"),
      std::string::npos);
  // A key of another decider's section is unknown there.
  EXPECT_NE(
      loadError("[EdgeRegistrationDeciderParameters]\noptimize_min_chi2 = 3\n")
          .find("[EdgeRegistrationDeciderParameters] unknown key 'optimize_min_chi2'"),
      std::string::npos);
  // MRPT's own keys are accepted in its sections.
  EXPECT_EQ(
      loadError("[GeneralConfiguration]\nclass_verbosity = 2\nsave_map = false\n"
                "[OptimizerParameters]\noptimization_distance = 3\nmax_iterations = 10\n"),
      "");
  // roi-graphslam's sections and our keys in MRPT's would be read half.
  EXPECT_NE(
      loadError("[GraphSlam]\nloop_min_inliers = 30\n[EdgeRegistrationDeciderParameters]\n"
                "loop_min_keyframe_gap = 4\n")
          .find("[EdgeRegistrationDeciderParameters] loop_min_keyframe_gap: this ini uses "
                "roi-graphslam's sections"),
      std::string::npos);
  // The old layout still reads (and names its sections).
  EXPECT_NE(
      loadError("[GraphSlam]\nloop_min_inliers = 2\n")
          .find("[GraphSlam] loop_min_inliers: must be >= 3"),
      std::string::npos);
}

TEST(SlamIni, DecidersByNameLoadAndPrintTheirParameters)
{
  const std::string dir = roislam::testing::makeTempDir("slam_ini");
  const std::string ini = dir + "/engine.ini";
  std::ofstream(ini) << "[NodeRegistrationDeciderParameters]\nkeyframe_rotation_deg = 7\n"
                        "[FeatureExtractor]\nfeature_type = sift\n"
                        "[EdgeRegistrationDeciderParameters]\nloop_min_inliers = 40\n"
                        "[OptimizerParameters]\noptimize_window_keyframes = 20\n";
  auto d = graphslam::CRoislamOptionsChecker().createDeciders({});
  EXPECT_EQ(d.context->configOrigin(), graphslam::CSlamContext::EConfigOrigin::DecidersLoadParams);
  // What MRPT's engine does in its constructor.
  d.node->loadParams(ini);
  d.edge->loadParams(ini);
  d.optimizer->loadParams(ini);
  const auto& c = d.context->config();
  EXPECT_DOUBLE_EQ(c.frontEnd.keyframe_rotation_deg, 7);
  EXPECT_EQ(c.frontEnd.extractor.feature_type, roislam::features::EFeatureType::SIFT);
  EXPECT_EQ(c.backEnd.loop_min_inliers, 40);
  EXPECT_EQ(c.backEnd.optimize_window_keyframes, 20);
  // The rebuilt front end uses them.
  EXPECT_DOUBLE_EQ(d.context->odometry().options().keyframe_rotation_deg, 7);

  ::testing::internal::CaptureStdout();
  d.node->printParams();
  d.edge->printParams();
  d.optimizer->printParams();
  const std::string printed = ::testing::internal::GetCapturedStdout();
  for (const char* line :
       {"CKeyframeNRD parameters (ini ", "[NodeRegistrationDeciderParameters]\n",
        "\nkeyframe_rotation_deg = 7.000000\n", "\nkeyframe_translation_m = 0.100000  (default)\n",
        "[FeatureExtractor]\n", "\nfeature_type = sift\n", "[GeneralConfiguration]\n",
        "CKeyframeERD parameters", "\nloop_min_inliers = 40\n",
        "\nloop_min_keyframe_gap = 10  (default)\n", "[LandmarkDatabase]\n",
        "CKeyframeGSO parameters", "[OptimizerParameters]\n", "\noptimize_window_keyframes = 20\n",
        "\noptimize_min_chi2 = 30.000000  (default)\n"})
    EXPECT_NE(printed.find(line), std::string::npos) << line << "\n" << printed;
  std::string report;
  d.optimizer->getDescriptiveReport(&report);
  EXPECT_NE(report.find("\noptimize_window_keyframes = 20\n"), std::string::npos) << report;

  // A context given whole by its creator is not re-read.
  graphslam::CSlamContext::TConfig given;
  given.backEnd.loop_min_inliers = 33;
  auto g = graphslam::CRoislamOptionsChecker().createDeciders({}, &given);
  g.edge->loadParams(ini);
  EXPECT_EQ(g.context->config().backEnd.loop_min_inliers, 33);
  ::testing::internal::CaptureStdout();
  g.edge->printParams();
  EXPECT_NE(
      ::testing::internal::GetCapturedStdout().find("(given by the caller)"), std::string::npos);

  // A missing ini is an error, not defaults.
  auto m = graphslam::CRoislamOptionsChecker().createDeciders({});
  EXPECT_THROW(m.node->loadParams(dir + "/missing.ini"), std::runtime_error);
  std::filesystem::remove_all(dir);
}
