// bench::CPairedSlamCost on the generated textured sequence (synthetic_data
// fixture): one row per version, every frame run, sane figures, and the
// reference version's ratios to itself exactly 1.
#include <gtest/gtest.h>
#include <roislam/bench/CPairedSlamCost.h>
#include <roislam/testing/TestData.h>

#include <filesystem>
#include <fstream>
#include <string>

using namespace roislam::bench;
namespace fs = std::filesystem;

namespace
{
/** Colour frames listed in a TUM folder's rgb.txt. */
std::size_t tumFrames(const std::string& seq)
{
  std::ifstream in(seq + "/rgb.txt");
  std::size_t n = 0;
  std::string line;
  while (std::getline(in, line))
    n += !line.empty() && line[0] != '#';
  return n;
}

CPairedSlamCost::TOptions shippedVersions(const std::string& seq)
{
  const std::string cfg = roislam::testing::sourceDir() + "/config";
  CPairedSlamCost::TOptions o;
  o.sequence = seq;
  o.feature = roislam::features::EFeatureType::ORB;
  o.max_features = 600;
  o.passes = 1;
  o.versions = {
      {"traditional", "", cfg + "/traditional.ini", {}},
      {"roi_big", "", cfg + "/roi_big.ini", {}},
      // roi-bench's image variant: an override of the ROI config.
      {"roi_big/image",
       "",
       cfg + "/roi_big.ini",
       {{"FrontEnd", "strict_roi", "false"},
        {"FrontEnd", "roi_feature_cap", "image"},
        {"FrontEnd", "roi_extraction", "image"}}}};
  return o;
}
}  // namespace

TEST(CPairedSlamCost, oneRowPerVersionOverTheWholeSequence)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "textured");
  const std::size_t frames = tumFrames(seq);
  ASSERT_GT(frames, 10u);
  const TPairedCost cost = CPairedSlamCost(shippedVersions(seq)).run();
  ASSERT_EQ(cost.versions.size(), 3u);
  EXPECT_TRUE(cost.ok());
  EXPECT_EQ(cost.feature, "orb");
  EXPECT_EQ(cost.passes, 1);
  EXPECT_EQ(cost.versions[2].key, "roi_big/image");
  for (const auto& v : cost.versions)
  {
    EXPECT_EQ(v.frames, frames) << v.key;
    EXPECT_EQ(v.lostFrames, 0u) << v.key;
    EXPECT_GT(v.wallMsPerFrame, 0) << v.key;
    EXPECT_GT(v.cpuMsPerFrame, 0) << v.key;
    EXPECT_GT(v.frontEndMsPerFrame, 0) << v.key;
    // The front end is a part of the step.
    EXPECT_LT(v.frontEndMsPerFrame, v.wallMsPerFrame) << v.key;
    EXPECT_NEAR(v.fps, 1e3 / v.wallMsPerFrame, 1e-9) << v.key;
    EXPECT_GT(v.wallRatio, 0) << v.key;
    EXPECT_GT(v.frontEndRatio, 0) << v.key;
    // The synthetic sequence has ground truth; a loose bound (the pipeline's
    // own tests bound it tightly).
    ASSERT_TRUE(v.ateRmse) << v.key;
    EXPECT_LT(*v.ateRmse, 0.1) << v.key;
  }
  EXPECT_EQ(cost.versions[0].wallRatio, 1.0);
  EXPECT_EQ(cost.versions[0].cpuRatio, 1.0);
  EXPECT_EQ(cost.versions[0].frontEndRatio, 1.0);
}

TEST(CPairedSlamCost, frameLimitAndPasses)
{
  ROISLAM_REQUIRE_SYNTHETIC(seq, "textured");
  auto o = shippedVersions(seq);
  o.versions.resize(2);
  o.max_frames = 8;
  o.passes = 2;
  const TPairedCost cost = CPairedSlamCost(o).run();
  ASSERT_EQ(cost.versions.size(), 2u);
  EXPECT_EQ(cost.maxFrames, 8u);
  for (const auto& v : cost.versions)
    EXPECT_EQ(v.frames, 8u) << v.key;  // per pass
}

TEST(CPairedSlamCost, badConfigsAreOneLineErrorsNamingTheFile)
{
  auto o = shippedVersions("/nonexistent");
  const auto message = [&]() -> std::string
  {
    try
    {
      CPairedSlamCost c(o);
    }
    catch (const std::exception& e)
    {
      return e.what();
    }
    return "";
  };
  o.versions[1].iniFile = "/nonexistent/roi_big.ini";
  std::string m = message();
  EXPECT_NE(m.find("/nonexistent/roi_big.ini"), std::string::npos) << m;
  EXPECT_EQ(m.find('\n'), std::string::npos) << m;

  // An override the config does not know: named with the file.
  o = shippedVersions("/nonexistent");
  o.versions[2].overrides.push_back({"FrontEnd", "no_such_key", "1"});
  m = message();
  EXPECT_NE(m.find("roi_big.ini"), std::string::npos) << m;
  EXPECT_NE(m.find("no_such_key"), std::string::npos) << m;
  EXPECT_EQ(m.find('\n'), std::string::npos) << m;

  o = shippedVersions("/nonexistent");
  o.versions.clear();
  EXPECT_THROW(CPairedSlamCost{o}, std::invalid_argument);
  o = shippedVersions("/nonexistent");
  o.passes = 0;
  EXPECT_THROW(CPairedSlamCost{o}, std::invalid_argument);
}
