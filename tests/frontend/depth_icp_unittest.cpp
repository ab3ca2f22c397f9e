// Depth ICP (libs/frontend/src/CDepthIcp.h) on the synthetic room: it aligns
// two views to the true relative pose, and it stops once its steps are within
// its own noise (icp_converged_step_sigma) instead of running every iteration
// for steps no larger than that noise.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "CDepthIcp.h"
#include "RigidMath.h"
#include "SyntheticRoom.h"

using roislam::frontend::detail::CDepthIcp;
using roislam::frontend::detail::fromPose;
using roislam::frontend::detail::leftDifference;
using roislam::frontend::detail::TRigid;
using roislam::frontend::detail::Vector6d;
namespace rt = roislam::frontend::testing;

namespace
{
/** The room's depth seen from `pose`, with Kinect-like noise (sigma
 *  1.425e-3 z^2 m, Khoshelham and Elberink) when `rng` is given. */
cv::Mat roomDepth(const mrpt::poses::CPose3D& pose, std::mt19937* rng)
{
  cv::Mat depth = rt::renderRoom(pose, 0, 0, 0).depth;
  if (rng)
  {
    std::normal_distribution<float> n(0.f, 1.f);
    for (auto it = depth.begin<float>(); it != depth.end<float>(); ++it)
      if (*it > 0)
        *it += 1.425e-3f * *it * *it * n(*rng);
  }
  return depth;
}

const mrpt::poses::CPose3D kRef(0.1, -0.05, 0.2, 0.05, -0.03, 0.02);
// 2 cm and about 1.2 degrees from the reference.
const mrpt::poses::CPose3D kCur(0.115, -0.04, 0.21, 0.065, -0.025, 0.028);

/** Where the current frame's points lie in the reference frame. */
TRigid truth()
{
  return fromPose(kCur - kRef);
}
}  // namespace

TEST(DepthIcp, AlignsTwoViewsOfTheRoomToTheTruePose)
{
  const CDepthIcp icp(CDepthIcp::TParams{}, rt::syntheticCamera());
  const auto ref = icp.buildMap(roomDepth(kRef, nullptr));
  const auto cur = icp.buildMap(roomDepth(kCur, nullptr));
  const auto r = icp.align(ref, cur, TRigid{});
  ASSERT_TRUE(r.has_value());
  const Vector6d e = leftDifference(truth(), r->T);
  EXPECT_LT(e.head<3>().norm(), 1e-3) << e.transpose();
  EXPECT_LT(e.tail<3>().norm(), 0.05 * M_PI / 180) << e.transpose();
  EXPECT_GT(r->pairs, 10000u);
  EXPECT_GE(r->iterations, 4);  // one tight-gate iteration at least
  EXPECT_LE(r->iterations, icp.params().maxIterations);
}

TEST(DepthIcp, StopsOnceItsStepsAreWithinItsOwnNoise)
{
  std::mt19937 rng(7);
  CDepthIcp::TParams p;
  p.maxIterations = 40;
  const cv::Mat refDepth = roomDepth(kRef, &rng), curDepth = roomDepth(kCur, &rng);
  CDepthIcp::TParams floorOnly = p;
  floorOnly.convergedStepSigma = 0;
  const CDepthIcp icp(p, rt::syntheticCamera()), full(floorOnly, rt::syntheticCamera());
  const auto ref = icp.buildMap(refDepth), cur = icp.buildMap(curDepth);
  const auto early = icp.align(ref, cur, TRigid{});
  const auto late = full.align(ref, cur, TRigid{});
  ASSERT_TRUE(early && late);
  // Noisy depth keeps re-pairing cells: the absolute floor (10 um) is reached
  // late or never, the step-within-noise rule stops earlier.
  EXPECT_LT(early->iterations, late->iterations);
  // What the further iterations changed is within a standard deviation of
  // the information ICP claims, and both are near the truth.
  const Vector6d d = leftDifference(late->T, early->T);
  const double apartSigma = std::sqrt(d.dot(late->information * d));
  std::printf(
      "iterations %d / %d, apart %.3f sigma\n", early->iterations, late->iterations, apartSigma);
  EXPECT_LT(apartSigma, 1.0) << d.transpose();
  for (const auto* r : {&*early, &*late})
  {
    const Vector6d e = leftDifference(truth(), r->T);
    EXPECT_LT(e.head<3>().norm(), 5e-3) << e.transpose();
    EXPECT_LT(e.tail<3>().norm(), 0.1 * M_PI / 180) << e.transpose();
  }
}
