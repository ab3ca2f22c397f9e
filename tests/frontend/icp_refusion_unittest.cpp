// Depth ICP fused into a registration (libs/frontend/src/OdometryWork.h:
// detail::fuseDepthIcp, detail::depthIcpJoins): the rule by which it joins
// a registration other than the one it was fused with (a keyframe's
// whole-image registration, makeKeyframeConstraints), and what fusing does.
#include <gtest/gtest.h>

#include "OdometryWork.h"

namespace detail = roislam::frontend::detail;
using detail::Matrix6d;
using detail::Vector6d;

namespace
{
detail::TRegistration registration(double sigmaM, const Vector6d& at)
{
  detail::TRegistration r;
  r.T = detail::applyLeft(at, detail::TRigid());
  Vector6d d;
  d << 1 / (sigmaM * sigmaM), 1 / (sigmaM * sigmaM), 1 / (sigmaM * sigmaM), 1e6, 1e6, 1e6;
  r.information = d.asDiagonal();
  r.edgeInformation = r.information;
  r.inliers = 200;
  return r;
}

detail::TFusedIcp icp(double sigmaM, const Vector6d& at, double scale)
{
  detail::TFusedIcp f;
  f.icp.T = detail::applyLeft(at, detail::TRigid());
  Vector6d d;
  d << 1 / (sigmaM * sigmaM), 1 / (sigmaM * sigmaM), 1 / (sigmaM * sigmaM), 4e6, 4e6, 4e6;
  f.icp.information = d.asDiagonal();
  f.icp.edgeInformation = f.icp.information;
  f.icp.pairs = 5000;
  f.scale = scale;
  return f;
}

Vector6d offset(double x)
{
  Vector6d v = Vector6d::Zero();
  v(0) = x;
  return v;
}
}  // namespace

TEST(IcpRefusion, JoinsByTheRuleOfTheRegistrationItWasFusedWith)
{
  roislam::frontend::CRgbdOdometry::TOptions o;
  o.icp_refine_sigma_m = 0.01;
  const auto f = icp(0.001, offset(0.0005), 2.0);

  // Poorly determined (20 mm beyond 10 mm): ICP carries the pose, always.
  o.icp_fusion = "weak";
  EXPECT_TRUE(detail::depthIcpJoins(registration(0.02, offset(0.05)), f, o));
  // Well determined (2 mm): weak fusion leaves it alone.
  EXPECT_FALSE(detail::depthIcpJoins(registration(0.002, Vector6d::Zero()), f, o));

  // Measured fusion: a well-determined one where both agree (0.5 mm apart,
  // well within 2 mm and 1.4 mm scaled).
  o.icp_fusion = "measured";
  EXPECT_TRUE(detail::depthIcpJoins(registration(0.002, Vector6d::Zero()), f, o));
  // ... but not where they disagree beyond what the scale explains (3 cm).
  EXPECT_FALSE(detail::depthIcpJoins(registration(0.002, offset(0.0305)), f, o));
}

TEST(IcpRefusion, FusingAddsTheScaledInformationAndMovesThePose)
{
  auto r = registration(0.002, Vector6d::Zero());
  const auto f = icp(0.001, offset(0.001), 2.0);
  const Matrix6d before = r.information;
  detail::fuseDepthIcp(r, f);
  EXPECT_TRUE(r.information.isApprox(before + f.icp.information / 2.0));
  EXPECT_TRUE(r.edgeInformation.isApprox(before + f.icp.edgeInformation / 2.0));
  // x: 1/(2 mm)^2 against 1/(1 mm)^2 / 2 = twice the weight: 2/3 of the way.
  EXPECT_NEAR(r.T.t.x(), 0.001 * 2.0 / 3.0, 1e-6);
  EXPECT_NEAR(r.T.t.y(), 0.0, 1e-9);
}
