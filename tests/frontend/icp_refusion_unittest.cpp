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

TEST(IcpRefusion, DepthIcpsShareOfTheFusedInformation)
{
  // Equal information on both sides: half. The keyframe policy takes ICP
  // as carrying the frame beyond that (StageKeyframe.cpp).
  auto reg = registration(0.001, Vector6d::Zero());
  reg.information.diagonal().tail<3>().setConstant(4e6);
  const auto equal = icp(0.001, Vector6d::Zero(), 1.0);
  detail::fuseDepthIcp(reg, equal);
  EXPECT_NEAR(detail::depthIcpShare(reg, equal), 0.5, 1e-9);

  // Scaled down 9x by what its disagreement measured: a tenth.
  auto reg9 = registration(0.001, Vector6d::Zero());
  reg9.information.diagonal().tail<3>().setConstant(4e6);
  const auto scaled = icp(0.001, Vector6d::Zero(), 9.0);
  detail::fuseDepthIcp(reg9, scaled);
  EXPECT_NEAR(detail::depthIcpShare(reg9, scaled), 0.1, 1e-9);

  // Features of a tenth of ICP's precision (10 mm against 1 mm, 100x less
  // information in translation): ICP carries most of the pose.
  auto weak = registration(0.01, Vector6d::Zero());
  const auto strong = icp(0.001, Vector6d::Zero(), 1.0);
  detail::fuseDepthIcp(weak, strong);
  EXPECT_GT(detail::depthIcpShare(weak, strong), 0.5);

  // A singular registration has no share to give.
  detail::TRegistration singular;
  singular.information = Matrix6d::Zero();
  EXPECT_EQ(detail::depthIcpShare(singular, strong), 0.0);
}
