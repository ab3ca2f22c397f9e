/* The SLAM accuracy targets on the shared fr1/rpy sequence (250 frames, 600
 * features, the shipped configs), for each extractor: every mode tracks every
 * frame; traditional ATE <= 0.03 m; big ROI within 10 % of traditional or
 * better. Prints the figures. Skips when the shared data are absent. */
#include <gtest/gtest.h>
#include <roislam/common/ProcessTuning.h>
#include <roislam/graphslam/CRoiGraphSlamApp.h>
#include <roislam/testing/TestData.h>

#include <cstdio>
#include <filesystem>
#include <string>

using roislam::graphslam::CRoiGraphSlamApp;

namespace
{
CRoiGraphSlamApp::TSummary runMode(
    const std::string& seq, const std::string& mode, const std::string& feature)
{
  // As the apps do: per-frame image buffers stay on the heap (SIFT).
  roislam::common::tuneAllocatorForImages();
  CRoiGraphSlamApp::TArguments a;
  a.iniFile = roislam::testing::sourceDir() + "/config/" + mode + ".ini";
  a.input = seq;
  a.outputDir = roislam::testing::makeTempDir("gs_tum_" + mode + "_" + feature);
  a.feature = feature;
  a.maxFeatures = 600;
  a.snapshot = false;
  const auto s = CRoiGraphSlamApp(a).run();
  std::filesystem::remove_all(a.outputDir);
  return s;
}
}  // namespace

class TumAccuracy : public ::testing::TestWithParam<std::string>
{
};

TEST_P(TumAccuracy, EveryModeCompleteAndBigRoiWithinTenPercent)
{
  ROISLAM_REQUIRE_SHARED_TUM(seq);
  const std::string feature = GetParam();
  double trad = 0;
  for (const std::string mode : {"traditional", "roi_small", "roi_big"})
  {
    const auto s = runMode(seq, mode, feature);
    std::printf(
        "%-5s %-12s ATE %.4f m, %zu keyframes, %zu loop closures, %zu fallback, %.1f fps\n",
        feature.c_str(), mode.c_str(), s.ateRmse.value_or(-1), s.keyframes, s.loopClosures,
        s.fallbackFrames, s.fps);
    EXPECT_EQ(s.trackedFrames, s.frames) << mode;
    EXPECT_EQ(s.lostFrames, 0u) << mode;
    EXPECT_FALSE(s.failed) << mode;
    ASSERT_TRUE(s.ateRmse.has_value()) << mode;
    if (mode == "traditional")
    {
      trad = *s.ateRmse;
      EXPECT_LE(trad, 0.03);
    }
    else if (mode == "roi_big")
      EXPECT_LE(*s.ateRmse, 1.10 * trad) << "big ROI vs traditional " << trad;
    else
      EXPECT_LE(*s.ateRmse, 0.035) << mode;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Fr1Rpy, TumAccuracy, ::testing::Values("orb", "surf", "sift"),
    [](const ::testing::TestParamInfo<std::string>& i) { return i.param; });
