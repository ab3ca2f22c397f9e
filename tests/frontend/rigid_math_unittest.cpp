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
