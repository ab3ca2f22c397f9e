// geometry::alignRigid and collinear(): the exact motion from exact points,
// the least-squares one from noisy points (no better motion nearby), a proper
// rotation where a reflection fits better, and the collinear cases.
#include <gtest/gtest.h>
#include <roislam/geometry/RigidAlignment.h>

#include <Eigen/Geometry>
#include <random>

using roislam::geometry::alignRigid;
using roislam::geometry::collinear;
using roislam::geometry::gatherPairs;
using roislam::geometry::TRigid;

namespace
{
TRigid motion()
{
  TRigid T;
  T.R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(0.3, -1.0, 0.5).normalized()).toRotationMatrix();
  T.t = Eigen::Vector3d(0.4, -1.2, 2.5);
  return T;
}

Eigen::Matrix3Xd randomPoints(int n, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  Eigen::Matrix3Xd P(3, n);
  for (int k = 0; k < n; ++k)
    P.col(k) = Eigen::Vector3d(u(rng), u(rng), 3.0 + u(rng));
  return P;
}

double sumSq(const TRigid& T, const Eigen::Matrix3Xd& a, const Eigen::Matrix3Xd& b)
{
  double s = 0;
  for (int k = 0; k < a.cols(); ++k)
    s += (a.col(k) - T * Eigen::Vector3d(b.col(k))).squaredNorm();
  return s;
}
}  // namespace

TEST(RigidAlignment, ExactPointsGiveTheExactMotion)
{
  const TRigid truth = motion();
  for (int n : {3, 4, 50})
  {
    const Eigen::Matrix3Xd b = randomPoints(n, 1);
    const Eigen::Matrix3Xd a = (truth.R * b).colwise() + truth.t;
    const TRigid T = alignRigid(a, b);
    EXPECT_LT((T.R - truth.R).norm(), 1e-12) << n;
    EXPECT_LT((T.t - truth.t).norm(), 1e-12) << n;
    EXPECT_NEAR(T.R.determinant(), 1.0, 1e-12);
  }
}

TEST(RigidAlignment, NoisyPointsGiveTheLeastSquaresMotion)
{
  const TRigid truth = motion();
  const Eigen::Matrix3Xd b = randomPoints(200, 2);
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0, 0.01);
  Eigen::Matrix3Xd a = (truth.R * b).colwise() + truth.t;
  for (int k = 0; k < a.cols(); ++k)
    a.col(k) += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
  const TRigid T = alignRigid(a, b);
  EXPECT_LT(Eigen::AngleAxisd(T.R * truth.R.transpose()).angle(), 2e-3);
  // A minimum: every small rotation or translation away costs more.
  const double best = sumSq(T, a, b);
  EXPECT_LT(best, sumSq(truth, a, b));
  for (int axis = 0; axis < 3; ++axis)
    for (double step : {-1e-4, 1e-4})
    {
      TRigid P = T;
      P.R = Eigen::AngleAxisd(step, Eigen::Vector3d::Unit(axis)) * T.R;
      EXPECT_GT(sumSq(P, a, b), best);
      P = T;
      P.t(axis) += step;
      EXPECT_GT(sumSq(P, a, b), best);
    }
}

TEST(RigidAlignment, AMirroredSetStillGivesAProperRotation)
{
  Eigen::Matrix3Xd b = randomPoints(20, 4);
  Eigen::Matrix3Xd a = b;
  a.row(0) *= -1;  // a reflection fits exactly; the rotation must stay proper
  const TRigid T = alignRigid(a, b);
  EXPECT_NEAR(T.R.determinant(), 1.0, 1e-12);
  EXPECT_NEAR((T.R * T.R.transpose() - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-12);
}

TEST(RigidAlignment, CollinearPoints)
{
  Eigen::Matrix3Xd line(3, 10);
  for (int k = 0; k < 10; ++k)
    line.col(k) = Eigen::Vector3d(0.1 * k, 0.05 * k, 1.0 - 0.02 * k);
  EXPECT_TRUE(collinear(line));
  EXPECT_TRUE(collinear(Eigen::Matrix3d(line.leftCols<3>())));
  EXPECT_TRUE(collinear(line.leftCols<2>()));
  line(1, 4) += 1e-3;  // 1 mm off the line: determined
  EXPECT_FALSE(collinear(line));
  EXPECT_FALSE(collinear(randomPoints(3, 5)));
  // The alignment of collinear points is still a least-squares one (the ATE
  // of a straight trajectory): exact points are mapped exactly.
  line(1, 4) -= 1e-3;
  const TRigid truth = motion();
  const Eigen::Matrix3Xd a = (truth.R * line).colwise() + truth.t;
  EXPECT_LT(sumSq(alignRigid(a, line), a, line), 1e-20);
}

TEST(RigidAlignment, GatherPairs)
{
  const std::vector<Eigen::Vector3d> a{{1, 0, 0}, {2, 0, 0}, {3, 0, 0}},
      b{{0, 1, 0}, {0, 2, 0}, {0, 3, 0}};
  const auto [A, B] = gatherPairs(a, b, {2, 0});
  ASSERT_EQ(A.cols(), 2);
  EXPECT_EQ(A.col(0), a[2]);
  EXPECT_EQ(B.col(1), b[0]);
  EXPECT_EQ(gatherPairs(a, b).first.cols(), 3);
  EXPECT_THROW(gatherPairs(a, b, {3}), std::out_of_range);
  EXPECT_THROW(gatherPairs(a, {}), std::invalid_argument);
  EXPECT_THROW(alignRigid(Eigen::Matrix3Xd(3, 2), Eigen::Matrix3Xd(3, 3)), std::invalid_argument);
}

TEST(TRigid, PoseRoundTripAndInverse)
{
  const TRigid T = motion();
  const TRigid back = TRigid::fromPose(T.toPose());
  EXPECT_LT((back.R - T.R).norm(), 1e-15);
  EXPECT_EQ(back.t, T.t);
  const Eigen::Vector3d p(0.3, 0.2, 1.0);
  EXPECT_LT((T.inverse() * (T * p) - p).norm(), 1e-14);
}
