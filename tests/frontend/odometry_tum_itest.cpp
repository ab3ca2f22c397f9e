// Odometry only (no back end) on the shared TUM sequence fr1/rpy (first 250
// frames): drift must stay bounded and every frame must be tracked.
#include <gtest/gtest.h>
#include <roislam/testing/TestData.h>

#include <iostream>

#include "OdometryRun.h"

using roislam::frontend::CRgbdOdometry;
using roislam::frontend::ETrackingMethod;

TEST(OdometryTum, OrbTraditionalDriftBounded)
{
  ROISLAM_REQUIRE_SHARED_TUM(dir);
  CRgbdOdometry::TOptions o;
  o.extractor.feature_type = roislam::features::EFeatureType::ORB;
  o.extractor.max_features = 600;
  const auto s = roislam::frontend::testing::runOdometry(dir, o);
  ASSERT_TRUE(s.ate.has_value());
  std::cout << "orb traditional: frames " << s.results.size() << " keyframes " << s.keyframes.size()
            << " ATE " << *s.ate << " m, " << s.results.size() / s.wallSeconds
            << " fps (with decoding), process " << s.processMs / s.results.size()
            << " ms/frame; features " << s.stats.features << " icp " << s.stats.depthIcp << " cv "
            << s.stats.constantVelocity << "\n";
  EXPECT_EQ(s.trajectory.size(), s.results.size());
  EXPECT_EQ(s.stats.lost, 0u);
  // Feature tracking must carry this textured desk scene on its own.
  EXPECT_GE(s.stats.features, s.results.size() * 95 / 100);
  EXPECT_LT(*s.ate, 0.10);
}
