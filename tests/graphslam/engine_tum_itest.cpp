/* roi-graphslam-engine (CRoiGraphSlamEngineApp: the deciders by name, their
 * parameters from config/graphslam-engine.ini in MRPT's sections) against
 * roi-graphslam (CRoiGraphSlamApp: config/<mode>.ini, its own layout, and
 * its command-line overrides) on tum2rawlog rawlogs of the shared fr1
 * excerpts: the same node and edge counts and an ATE within 2 % (the same
 * code path: in fact equal). The default suite runs one mode on each excerpt;
 * every mode and extractor on both excerpts runs with ROISLAM_ENGINE_TUM_ALL=1,
 * as the slow-labelled ctest graphslam_engine_tum_all does. Skips when the
 * shared data are absent. */
#include <gtest/gtest.h>
#include <roislam/common/ProcessTuning.h>
#include <roislam/graphslam/CRoiGraphSlamApp.h>
#include <roislam/graphslam/CRoiGraphSlamEngineApp.h>
#include <roislam/io/CTum2RawlogApp.h>
#include <roislam/testing/TestData.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <string>

#include "EngineIni.h"

namespace fs = std::filesystem;
namespace graphslam = roislam::graphslam;

namespace
{
struct TSequence
{
  std::string rawlog, groundTruth;
};

/** The excerpt as a rawlog (made once per test program), or nullopt. */
std::optional<TSequence> rawlogOf(const std::string& name)
{
  static std::map<std::string, TSequence> made;
  static const roislam::testing::CTempDir dir("engine_tum");
  const fs::path folder = fs::path(roislam::testing::sharedDataDir()) / "tum" / name;
  if (!fs::exists(folder / "rgb.txt"))
    return std::nullopt;
  if (!made.count(name))
  {
    roislam::io::CTum2RawlogApp::TOptions o;
    o.input = folder.string();
    o.output = dir.path() + "/" + name + ".rawlog";
    o.camera = "fr1";
    const auto r = roislam::io::CTum2RawlogApp(o).run();
    made[name] = {r.rawlog, r.groundTruth.value_or("")};
  }
  return made[name];
}

std::string config(const std::string& name)
{
  return roislam::testing::sourceDir() + "/config/" + name;
}

void compare(const std::string& name, const std::string& mode, const std::string& feature)
{
  const auto seq = rawlogOf(name);
  ASSERT_TRUE(seq);
  roislam::common::tuneAllocatorForImages();
  const std::string dir = roislam::testing::makeTempDir("engine_tum_" + mode + "_" + feature);

  graphslam::CRoiGraphSlamApp::TArguments g;
  g.iniFile = config(mode + ".ini");
  g.input = seq->rawlog;
  g.outputDir = dir + "/roi-graphslam";
  g.feature = feature;
  g.snapshot = false;
  const auto a = graphslam::CRoiGraphSlamApp(g).run();

  graphslam::CRoiGraphSlamEngineApp::TArguments e;
  e.iniFile = roislam::testing::engineIniVariant(dir, mode, feature);
  e.rawlog = seq->rawlog;
  e.groundTruth = seq->groundTruth;
  e.outputDir = dir + "/engine";
  e.snapshot = false;
  const auto b = graphslam::CRoiGraphSlamEngineApp(e).run();

  ASSERT_TRUE(a.ateRmse && b.ateRmse);
  std::printf(
      "%s %-12s %-5s ATE roi-graphslam %.5f m, engine %.5f m; nodes %zu / %zu, edges %zu / %zu\n",
      name.c_str(), mode.c_str(), feature.c_str(), *a.ateRmse, *b.ateRmse, a.graphNodes,
      b.graphNodes, a.graphEdges, b.graphEdges);
  EXPECT_EQ(a.graphNodes, b.graphNodes);
  EXPECT_EQ(a.graphEdges, b.graphEdges);
  EXPECT_EQ(a.loopClosures, b.loopClosures);
  EXPECT_NEAR(*b.ateRmse, *a.ateRmse, 0.02 * *a.ateRmse);
  fs::remove_all(dir);
}
}  // namespace

// The default suite: one mode on each excerpt (the one with fast rotations in
// the traditional mode, the other in a ROI mode), about half a minute.
TEST(EngineOnTum, EqualsRoiGraphSlamOnFr1RpyTraditionalOrb)
{
  if (!rawlogOf("rgbd_dataset_freiburg1_rpy_first250"))
    GTEST_SKIP() << "shared TUM data not found under " << roislam::testing::sharedDataDir();
  compare("rgbd_dataset_freiburg1_rpy_first250", "traditional", "orb");
}

TEST(EngineOnTum, EqualsRoiGraphSlamOnFr1XyzBigRoiOrb)
{
  if (!rawlogOf("rgbd_dataset_freiburg1_xyz_first150"))
    GTEST_SKIP() << "shared TUM data not found under " << roislam::testing::sharedDataDir();
  compare("rgbd_dataset_freiburg1_xyz_first150", "roi_big", "orb");
}

TEST(EngineOnTum, EqualsRoiGraphSlamInEveryModeOnBothExcerpts)
{
  const char* all = std::getenv("ROISLAM_ENGINE_TUM_ALL");
  if (!all || std::string(all) != "1")
    GTEST_SKIP() << "every mode on both excerpts: set ROISLAM_ENGINE_TUM_ALL=1 (36 runs, "
                    "about 6 minutes on 2 cores)";
  for (const std::string name :
       {"rgbd_dataset_freiburg1_rpy_first250", "rgbd_dataset_freiburg1_xyz_first150"})
  {
    if (!rawlogOf(name))
      GTEST_SKIP() << "shared TUM data not found under " << roislam::testing::sharedDataDir();
    for (const std::string mode : {"traditional", "roi_small", "roi_big"})
      for (const std::string feature : {"orb", "surf", "sift"})
        compare(name, mode, feature);
  }
}
