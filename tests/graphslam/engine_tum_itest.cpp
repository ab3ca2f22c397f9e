/* roi-graphslam-engine (CRoiGraphSlamEngineApp: the deciders by name, their
 * parameters from config/graphslam-engine.ini in MRPT's sections) against
 * roi-graphslam (CRoiGraphSlamApp: config/<mode>.ini, its own layout, and
 * its command-line overrides) on tum2rawlog rawlogs of the shared fr1
 * excerpts: the same node, edge and loop-closure counts and an ATE within
 * 2 % (the same code path: in fact equal). One mode on each excerpt here (the
 * one with fast rotations in the traditional mode, the other in a ROI mode);
 * every mode with every extractor on both in engine_tum_slowtest. Skips when
 * the shared data are absent. */
#include <gtest/gtest.h>
#include <roislam/testing/TestData.h>

#include "EngineRuns.h"

TEST(EngineOnTum, EqualsRoiGraphSlamOnFr1RpyTraditionalOrb)
{
  const std::string name = "rgbd_dataset_freiburg1_rpy_first250";
  if (!roislam::testing::sharedExcerpt(name))
    GTEST_SKIP() << "shared TUM data not found under " << roislam::testing::sharedDataDir();
  roislam::testing::expectEngineEqualsRoiGraphSlam(name, "traditional", "orb");
}

TEST(EngineOnTum, EqualsRoiGraphSlamOnFr1XyzBigRoiOrb)
{
  const std::string name = "rgbd_dataset_freiburg1_xyz_first150";
  if (!roislam::testing::sharedExcerpt(name))
    GTEST_SKIP() << "shared TUM data not found under " << roislam::testing::sharedDataDir();
  roislam::testing::expectEngineEqualsRoiGraphSlam(name, "roi_big", "orb");
}
