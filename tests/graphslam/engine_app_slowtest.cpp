/* roi-graphslam-engine on a tum2rawlog rawlog of the synthetic textured loop
 * in every mode with every extractor (the default suite runs each mode and
 * each extractor once, engine_app_itest): every frame tracked, ATE < 1 cm,
 * RPE from -g, at least one loop closure, every output written. */
#include <gtest/gtest.h>
#include <roislam/testing/TestData.h>

#include <filesystem>
#include <string>

#include "EngineRuns.h"

TEST(RoiGraphSlamEngineApp, SyntheticLoopEveryModeWithEveryExtractor)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "textured");
  const auto& data = roislam::testing::rawlogOf(seq);
  const std::string out = roislam::testing::makeTempDir("engine_app_all");
  for (const std::string mode : {"traditional", "roi_small", "roi_big"})
    for (const std::string feature : {"orb", "surf", "sift"})
      roislam::testing::expectAccurateRun(data, out, mode, feature, false);
  std::filesystem::remove_all(out);
}
