// Odometry only on the shared fr1/rpy sequence for every extractor and mode
// (600 features): prints ATE, frames per second (with image decoding) and
// per-frame cost, and checks that no mode loses or badly drifts.
#include <gtest/gtest.h>
#include <roislam/testing/TestData.h>

#include <cstdio>

#include "OdometryRun.h"

using roislam::features::EFeatureType;
using roislam::frontend::CRgbdOdometry;
using roislam::frontend::EFrontEndMode;

TEST(OdometryTumSweep, AllExtractorsAndModes)
{
  ROISLAM_REQUIRE_SHARED_TUM(dir);
  std::printf(
      "%-6s %-12s %8s %7s %9s %6s %6s %6s %6s\n", "feat", "mode", "ATE[m]", "fps", "proc[ms]", "kf",
      "roi", "fallbk", "icp+cv");
  for (auto type : {EFeatureType::ORB, EFeatureType::SIFT, EFeatureType::SURF})
  {
    for (auto mode : {EFrontEndMode::Traditional, EFrontEndMode::RoiSmall, EFrontEndMode::RoiBig})
    {
      CRgbdOdometry::TOptions o;
      o.mode = mode;
      o.extractor.feature_type = type;
      o.extractor.max_features = 600;
      const auto s = roislam::frontend::testing::runOdometry(dir, o);
      ASSERT_TRUE(s.ate.has_value());
      const double n = static_cast<double>(s.results.size());
      std::printf(
          "%-6s %-12s %8.4f %7.1f %9.2f %6zu %6zu %6zu %6zu\n",
          roislam::features::toString(type).c_str(), toString(mode).c_str(), *s.ate,
          n / s.wallSeconds, s.processMs / n, s.keyframes.size(), s.stats.roiFeatures,
          s.stats.fullImageFallback, s.stats.depthIcp + s.stats.constantVelocity);
      std::fflush(stdout);
      EXPECT_EQ(s.stats.lost, 0u);
      EXPECT_EQ(s.trajectory.size(), s.results.size());
      EXPECT_LT(*s.ate, 0.15) << roislam::features::toString(type) << " " << toString(mode);
    }
  }
}
