/* The left-perturbation information of a registration carried to the
 * parametrisation MRPT's SPA weighs edges by (pseudo-log e of the right
 * perturbation T exp(e)): a small left perturbation d and the e it equals
 * have the same Mahalanobis length. */
#include <gtest/gtest.h>
#include <roislam/geometry/Rotation.h>

#include <Eigen/Dense>
#include <random>

#include "RigidMath.h"

namespace detail = roislam::frontend::detail;

TEST(RigidMath, PseudoLogInformationMatchesTheLeftPerturbation)
{
  std::mt19937 rng(3);
  std::normal_distribution<double> N(0, 1);
  for (int trial = 0; trial < 20; ++trial)
  {
    detail::Vector6d p;
    for (int k = 0; k < 6; ++k)
      p[k] = N(rng);
    detail::TRigid T;
    T.R = roislam::geometry::expSO3(0.5 * p.tail<3>());
    T.t = p.head<3>();
    detail::Matrix6d L = detail::Matrix6d::Random();
    const detail::Matrix6d H = L * L.transpose() + 0.1 * detail::Matrix6d::Identity();
    const detail::Matrix6d He = detail::tangentInfoToPseudoLog(H, T);
    detail::Vector6d d;
    for (int k = 0; k < 6; ++k)
      d[k] = 1e-5 * N(rng);
    // exp(d) T = T E: E = T^-1 exp(d) T, e = [t_E, log R_E].
    const detail::TRigid Tl = detail::applyLeft(d, T);
    const Eigen::Matrix3d RE = T.R.transpose() * Tl.R;
    const Eigen::Vector3d tE = T.R.transpose() * (Tl.t - T.t);
    detail::Vector6d e;
    e.head<3>() = tE;
    e.tail<3>() = roislam::geometry::logSO3(RE);
    const double a = d.dot(H * d), b = e.dot(He * e);
    EXPECT_NEAR(b / a, 1.0, 1e-3) << "trial " << trial;
  }
}

/* Chaining two registrations: a small left perturbation of each moves their
 * product by d_a + J d_b, J found by finite differences here; the composed
 * covariance must be Cov_a + J Cov_b J^T. */
TEST(RigidMath, ComposedInformationCarriesTheSecondPerturbationThroughTheFirst)
{
  std::mt19937 rng(5);
  std::normal_distribution<double> N(0, 1);
  auto randomRigid = [&]()
  {
    detail::Vector6d p;
    for (int k = 0; k < 6; ++k)
      p[k] = N(rng);
    detail::TRigid T;
    T.R = roislam::geometry::expSO3(0.7 * p.tail<3>());
    T.t = p.head<3>();
    return T;
  };
  auto product = [](const detail::TRigid& a, const detail::TRigid& b)
  {
    detail::TRigid o;
    o.R = a.R * b.R;
    o.t = a.R * b.t + a.t;
    return o;
  };
  auto randomInformation = [&]()
  {
    detail::Matrix6d L = detail::Matrix6d::Random();
    return detail::Matrix6d(L * L.transpose() + 0.2 * detail::Matrix6d::Identity());
  };
  for (int trial = 0; trial < 10; ++trial)
  {
    const detail::TRigid a = randomRigid(), b = randomRigid();
    const detail::TRigid ab = product(a, b);
    const double eps = 1e-6;
    detail::Matrix6d J;
    for (int k = 0; k < 6; ++k)
    {
      detail::Vector6d d = detail::Vector6d::Zero();
      d[k] = eps;
      const detail::Vector6d plus = detail::leftDifference(ab, product(a, detail::applyLeft(d, b)));
      const detail::Vector6d minus =
          detail::leftDifference(ab, product(a, detail::applyLeft(-d, b)));
      J.col(k) = (plus - minus) / (2 * eps);
    }
    const detail::Matrix6d Ha = randomInformation(), Hb = randomInformation();
    const auto H = detail::composedInformation(a, Ha, Hb);
    ASSERT_TRUE(H);
    const detail::Matrix6d expected = (Ha.inverse() + J * Hb.inverse() * J.transpose()).inverse();
    EXPECT_LT((*H - expected).norm(), 1e-5 * expected.norm()) << "trial " << trial;
    // The first's own perturbation enters unchanged: with b exact, a's alone.
    const auto alone = detail::composedInformation(a, Ha, 1e12 * detail::Matrix6d::Identity());
    ASSERT_TRUE(alone);
    EXPECT_LT((*alone - Ha).norm(), 1e-4 * Ha.norm());
  }
  // An undetermined direction in either: none.
  detail::Matrix6d singular = detail::Matrix6d::Identity();
  singular(2, 2) = 0;
  EXPECT_FALSE(detail::composedInformation(randomRigid(), singular, detail::Matrix6d::Identity()));
  EXPECT_FALSE(detail::composedInformation(randomRigid(), detail::Matrix6d::Identity(), singular));
}
