// worstSigmas: the worst-determined translation direction and rotation axis
// of a relative-pose information matrix (MRPT's x y z yaw pitch roll order).
#include <gtest/gtest.h>
#include <roislam/frontend/PoseUncertainty.h>

#include <cmath>
#include <limits>

using roislam::frontend::TInformation66;
using roislam::frontend::worstSigmas;

TEST(PoseUncertainty, DiagonalInformationGivesTheLargestSigmaOfEachBlock)
{
  TInformation66 info;
  info.setZero();
  const double sig[6] = {0.001, 0.004, 0.002, 0.01, 0.03, 0.02};
  for (int i = 0; i < 6; ++i)
    info(i, i) = 1.0 / (sig[i] * sig[i]);
  const auto s = worstSigmas(info);
  ASSERT_TRUE(s.has_value());
  EXPECT_NEAR(s->translation_m, 0.004, 1e-12);
  EXPECT_NEAR(s->rotation_rad, 0.03, 1e-12);
}

TEST(PoseUncertainty, CorrelationWidensTheMarginal)
{
  // x and pitch strongly coupled (a small ROI's ambiguity): the marginal of x
  // is much wider than 1/sqrt(info(x, x)).
  TInformation66 info;
  info.setIdentity();
  for (int i = 0; i < 6; ++i)
    info(i, i) = 1e6;
  info(0, 4) = info(4, 0) = 0.999 * 1e6;
  const auto s = worstSigmas(info);
  ASSERT_TRUE(s.has_value());
  EXPECT_NEAR(s->translation_m, 1e-3 / std::sqrt(1 - 0.999 * 0.999), 1e-6);
  EXPECT_GT(s->translation_m, 20e-3);
}

TEST(PoseUncertainty, SingularOrNonFiniteGivesNothing)
{
  TInformation66 info;
  info.setZero();
  EXPECT_FALSE(worstSigmas(info).has_value());
  info.setIdentity();
  info(2, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(worstSigmas(info).has_value());
}
