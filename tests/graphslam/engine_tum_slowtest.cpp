/* roi-graphslam-engine against roi-graphslam on tum2rawlog rawlogs of both
 * shared fr1 excerpts in every mode with every extractor (18 pairs of runs;
 * the default suite runs one pair per excerpt, engine_tum_itest): the same
 * node, edge and loop-closure counts and an ATE within 2 %. Skips when the
 * shared data are absent. */
#include <gtest/gtest.h>
#include <roislam/testing/TestData.h>

#include <string>

#include "EngineRuns.h"

TEST(EngineOnTum, EqualsRoiGraphSlamInEveryModeOnBothExcerpts)
{
  for (const std::string name :
       {"rgbd_dataset_freiburg1_rpy_first250", "rgbd_dataset_freiburg1_xyz_first150"})
  {
    if (!roislam::testing::sharedExcerpt(name))
      GTEST_SKIP() << "shared TUM data not found under " << roislam::testing::sharedDataDir();
    for (const std::string mode : {"traditional", "roi_small", "roi_big"})
      for (const std::string feature : {"orb", "surf", "sift"})
        roislam::testing::expectEngineEqualsRoiGraphSlam(name, mode, feature);
  }
}
