/* Closed-form least-squares rigid alignment of corresponding 3-D points (no
 * scale): the one implementation behind the matching RANSAC's minimal
 * samples and refits (CRigidTransformRansac, which the front end and the
 * landmarks use) and the ATE's trajectory alignment (CTrajectoryEvaluator,
 * as evaluate_ate.py's align(), which is the same SVD method).
 *
 * It is Eigen::umeyama without scale. Measured (tests/benchmark/
 * geometry_benchmark.cpp, 5 mm noise) all three candidates reach the
 * same optimum: rotations agree with each other to 1e-10 rad. Wall time per
 * call on the 2-core development machine (shared, median of 6):
 * 3 pairs: umeyama 0.56 us, mrpt::tfest::se3_l2 0.82 us, our former
 * hand-written SVD loop 0.57 us; 100 / 250 / 500 pairs: umeyama 1.4 / 2.6 /
 * 4.6 us, se3_l2 1.5 / 2.3 / 3.9 us, the loop 1.8 / 3.7 / 6.8 us.
 * se3_l2 wins only beyond ~250 pairs and needs TPoint3D copies and a
 * quaternion round trip; umeyama is as good everywhere else.
 * umeyama reports no degeneracy: collinear() below tests it where a caller
 * needs a determined rotation (the RANSAC; the ATE does not), 0.10 us on
 * 3 points.
 */
#pragma once

#include <roislam/geometry/TRigid.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <utility>
#include <vector>

namespace roislam::geometry
{
/** T minimising sum_k |a.col(k) - T * b.col(k)|^2 over the columns of two
 *  3 x n matrices: Eigen::umeyama without scale (a proper rotation by its
 *  sign correction). For (nearly) collinear b the rotation about their line
 *  is undetermined and T is one of the equally good ones: callers that need
 *  a determined rotation test collinear(b). Throws std::invalid_argument when
 *  the column counts differ or are 0. */
template <typename DerivedA, typename DerivedB>
TRigid alignRigid(const Eigen::MatrixBase<DerivedA>& a, const Eigen::MatrixBase<DerivedB>& b)
{
  static_assert(DerivedA::RowsAtCompileTime == 3 && DerivedB::RowsAtCompileTime == 3);
  if (a.cols() != b.cols() || a.cols() == 0)
    throw std::invalid_argument("alignRigid: point sets of different or zero size");
  const Eigen::Matrix4d M = Eigen::umeyama(b, a, false);
  TRigid T;
  T.R = M.topLeftCorner<3, 3>();
  T.t = M.topRightCorner<3, 1>();
  return T;
}

/** Whether the points (columns of a 3 x n matrix) lie (nearly) on a line:
 *  the second largest eigenvalue of their scatter about the mean is below
 *  1e-9 of max(1 m^2, the largest). Fewer than 3 points are collinear. */
template <typename Derived>
bool collinear(const Eigen::MatrixBase<Derived>& p)
{
  static_assert(Derived::RowsAtCompileTime == 3);
  if (p.cols() < 3)
    return true;
  const Eigen::Vector3d mean = p.rowwise().mean();
  const auto centred = (p.colwise() - mean).eval();
  const Eigen::Matrix3d scatter = centred * centred.transpose() / static_cast<double>(p.cols());
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(scatter, Eigen::EigenvaluesOnly);
  const Eigen::Vector3d ev = eig.eigenvalues();  // ascending
  return !(ev(1) > 1e-9 * std::max(1.0, ev(2)));
}

/** The points a[i], b[i] for i in indices (all when indices is empty) as
 *  3 x n matrices, for the two functions above. Throws std::invalid_argument
 *  when a and b differ in size, std::out_of_range on a bad index. */
std::pair<Eigen::Matrix3Xd, Eigen::Matrix3Xd> gatherPairs(
    const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b,
    const std::vector<std::size_t>& indices = {});
}  // namespace roislam::geometry
