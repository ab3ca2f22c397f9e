#include "roislam/frontend/PoseUncertainty.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace roislam::frontend
{
std::optional<TPoseSigmas> worstSigmas(const TInformation66& information)
{
  const Eigen::Matrix<double, 6, 6> I = information.asEigen();
  if (!I.allFinite())
    return std::nullopt;
  const Eigen::FullPivLU<Eigen::Matrix<double, 6, 6>> lu(I);
  if (!lu.isInvertible())
    return std::nullopt;
  const Eigen::Matrix<double, 6, 6> C = lu.inverse();
  const auto largest = [](const Eigen::Matrix3d& m)
  {
    const Eigen::Matrix3d sym = 0.5 * (m + m.transpose());
    return std::sqrt(std::max(
        0.0, Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(sym).eigenvalues().maxCoeff()));
  };
  TPoseSigmas s;
  s.translation_m = largest(C.topLeftCorner<3, 3>());
  s.rotation_rad = largest(C.bottomRightCorner<3, 3>());
  return s;
}
}  // namespace roislam::frontend
