#include "roislam/io/TumTrajectory.h"

#include <mrpt/math/CMatrixFixed.h>
#include <mrpt/poses/CPose3DQuat.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "TumTextFile.h"

namespace roislam::io
{
namespace
{
/** Pose from a (not necessarily unit) quaternion, built as the benchmark's
 *  evaluate_rpe.py transform44() does: q scaled by sqrt(2/|q|^2), then the
 *  outer-product form of the rotation matrix; a near-zero |q|^2 gives identity. */
/** Below this |q|^2 the scripts' transform44() returns the identity. */
constexpr double kMinQuaternionNorm2 = std::numeric_limits<double>::epsilon() * 4.0;

mrpt::poses::CPose3D poseFromTum(const std::array<double, 8>& v)
{
  const double eps = kMinQuaternionNorm2;
  std::array<double, 4> q = {v[4], v[5], v[6], v[7]};  // x y z w
  const double nq = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
  mrpt::math::CMatrixDouble33 R = mrpt::math::CMatrixDouble33::Identity();
  if (nq >= eps)
  {
    const double s = std::sqrt(2.0 / nq);
    for (auto& c : q)
      c *= s;
    auto Q = [&](int a, int b) { return q[a] * q[b]; };
    R(0, 0) = 1.0 - Q(1, 1) - Q(2, 2);
    R(0, 1) = Q(0, 1) - Q(2, 3);
    R(0, 2) = Q(0, 2) + Q(1, 3);
    R(1, 0) = Q(0, 1) + Q(2, 3);
    R(1, 1) = 1.0 - Q(0, 0) - Q(2, 2);
    R(1, 2) = Q(1, 2) - Q(0, 3);
    R(2, 0) = Q(0, 2) - Q(1, 3);
    R(2, 1) = Q(1, 2) + Q(0, 3);
    R(2, 2) = 1.0 - Q(0, 0) - Q(1, 1);
  }
  mrpt::math::CVectorFixedDouble<3> t;
  t[0] = v[1];
  t[1] = v[2];
  t[2] = v[3];
  return mrpt::poses::CPose3D(R, t);
}

}  // namespace

TTrajectory loadTumTrajectory(const std::string& file, EInvalidPose invalid)
{
  TTrajectory trajectory;
  for (const auto& row : tumtext::readRowsWithLines(file, 8, "timestamp tx ty tz qx qy qz qw"))
  {
    const auto& v = row.values;
    // The skips of evaluate_rpe.py's read_trajectory() (a NaN, a quaternion
    // of exactly zero), or an error naming the line.
    const double nq = v[4] * v[4] + v[5] * v[5] + v[6] * v[6] + v[7] * v[7];
    const bool zeroQuaternion = !row.hasNan && nq < kMinQuaternionNorm2;
    if ((row.hasNan || zeroQuaternion) && invalid == EInvalidPose::Reject)
      throw std::runtime_error(
          file + ":" + std::to_string(row.line) +
          (row.hasNan ? ": NaN value" : ": zero quaternion (no rotation)") +
          " (roi-eval --skip-invalid skips such lines as the benchmark scripts do)");
    if (row.hasNan || (v[4] == 0 && v[5] == 0 && v[6] == 0 && v[7] == 0))
      continue;
    std::array<double, 8> a{};
    std::copy(v.begin(), v.end(), a.begin());
    trajectory.push_back({a[0], poseFromTum(a)});
  }

  // Stable, so a repeated stamp keeps file order (the scripts' dicts keep the last).
  std::stable_sort(
      trajectory.begin(), trajectory.end(),
      [](const TPoseStamped& a, const TPoseStamped& b) { return a.timestamp < b.timestamp; });
  return trajectory;
}

void saveTumTrajectory(
    const std::string& file, const TTrajectory& trajectory, const std::string& headerComment)
{
  using tumtext::formatDouble;
  std::ostringstream out;
  out << tumtext::commentLines(headerComment) << "# timestamp tx ty tz qx qy qz qw\n";
  for (const auto& p : trajectory)
  {
    const mrpt::poses::CPose3DQuat pq(p.pose);
    double w = pq.quat().r(), x = pq.quat().x(), y = pq.quat().y(), z = pq.quat().z();
    const double n = std::sqrt(w * w + x * x + y * y + z * z);
    const double sign = (w < 0) ? -1.0 : 1.0;
    w *= sign / n;
    x *= sign / n;
    y *= sign / n;
    z *= sign / n;
    out << formatDouble(p.timestamp) << ' ' << formatDouble(p.pose.x()) << ' '
        << formatDouble(p.pose.y()) << ' ' << formatDouble(p.pose.z()) << ' ' << formatDouble(x)
        << ' ' << formatDouble(y) << ' ' << formatDouble(z) << ' ' << formatDouble(w) << '\n';
  }
  tumtext::writeAtomically(file, out.str());
}
std::optional<mrpt::poses::CPose3D> poseAt(
    const TTrajectory& gt, double t, double maxDifference, bool interpolate)
{
  if (gt.empty())
    return std::nullopt;
  // First stamp >= t; the nearest stamp is it or its predecessor.
  const auto it = std::lower_bound(
      gt.begin(), gt.end(), t, [](const TPoseStamped& p, double v) { return p.timestamp < v; });
  const std::size_t hi = static_cast<std::size_t>(it - gt.begin());
  std::size_t nearest = hi;
  if (hi == gt.size() || (hi > 0 && t - gt[hi - 1].timestamp < gt[hi].timestamp - t))
    nearest = hi - 1;
  if (std::abs(gt[nearest].timestamp - t) > maxDifference)
    return std::nullopt;
  if (!interpolate || hi == 0 || hi == gt.size() || gt[hi].timestamp == t)
    return gt[nearest].pose;

  const auto& a = gt[hi - 1];
  const auto& b = gt[hi];
  const double s = (t - a.timestamp) / (b.timestamp - a.timestamp);
  const Eigen::Quaterniond qa(a.pose.getRotationMatrix().asEigen());
  const Eigen::Quaterniond qb(b.pose.getRotationMatrix().asEigen());
  const Eigen::Matrix3d R = qa.slerp(s, qb).toRotationMatrix();
  const auto ta = a.pose.translation();
  const auto tb = b.pose.translation();
  mrpt::math::CMatrixDouble33 Rm;
  Rm.asEigen() = R;
  return mrpt::poses::CPose3D(Rm, mrpt::math::CVectorFixedDouble<3>(ta + (tb - ta) * s));
}
}  // namespace roislam::io
