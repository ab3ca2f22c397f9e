// geometry::expSO3 / logSO3 / rotationAngle: proper rotations, exact round
// trips down to the tiny angles of Gauss-Newton steps, the identity below
// 1e-12 rad, and the angle at pi.
#include <gtest/gtest.h>
#include <roislam/geometry/Rotation.h>

#include <cmath>
#include <random>

using namespace roislam::geometry;

TEST(Rotation, ExpIsAProperRotationAndLogItsInverse)
{
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (double mag : {1e-10, 1e-7, 1e-4, 0.1, 1.0, 3.0})
    for (int i = 0; i < 50; ++i)
    {
      const Eigen::Vector3d w = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized() * mag;
      const Eigen::Matrix3d R = expSO3(w);
      EXPECT_NEAR(R.determinant(), 1.0, 1e-14);
      EXPECT_LT((R * R.transpose() - Eigen::Matrix3d::Identity()).norm(), 1e-14);
      // Relative accuracy holds for small angles too (an acos of the trace
      // would lose half the digits there).
      EXPECT_LT((logSO3(R) - w).norm(), 1e-14 * mag) << mag;
      EXPECT_NEAR(rotationAngle(R), mag, 1e-14 * std::max(1.0, mag)) << mag;
      // A point is turned by the angle about the axis.
      const Eigen::Vector3d p = w.unitOrthogonal();
      EXPECT_NEAR(std::acos(std::clamp(p.dot(R * p), -1.0, 1.0)), mag, 1e-7);
    }
}

TEST(Rotation, TinyAndHalfTurns)
{
  EXPECT_EQ(expSO3(Eigen::Vector3d(1e-13, 0, 0)), Eigen::Matrix3d::Identity());
  EXPECT_EQ(expSO3(Eigen::Vector3d::Zero()), Eigen::Matrix3d::Identity());
  EXPECT_EQ(logSO3(Eigen::Matrix3d::Identity()), Eigen::Vector3d::Zero());
  const Eigen::Matrix3d half = expSO3(Eigen::Vector3d(0, 0, M_PI));
  EXPECT_NEAR(rotationAngle(half), M_PI, 1e-12);
  EXPECT_NEAR(std::abs(logSO3(half).z()), M_PI, 1e-12);
}
