#include "roislam/io/TumTrajectory.h"

#include <mrpt/math/CMatrixFixed.h>
#include <mrpt/poses/CPose3DQuat.h>
#include <unistd.h>

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

namespace roislam::io
{
namespace
{
/** Parses one number like Python's float() on a stripped token (an optional
 *  leading '+' is allowed; "nan" is accepted and later skips the line). */
bool parseNumber(const std::string& token, double& value)
{
  const char* first = token.data();
  const char* last = token.data() + token.size();
  if (first != last && *first == '+')
    ++first;
  if (first == last)
    return false;
  const auto [ptr, ec] = std::from_chars(first, last, value);
  return ec == std::errc() && ptr == last;
}

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

/** Shortest text that reads back as exactly the same double. */
std::string formatDouble(double x)
{
  std::array<char, 400> buf{};
  // Shortest fixed-notation text that reads back exactly: TUM files never
  // use exponents (a stamp of 1e+09 would look foreign to other tools).
  const auto [ptr, ec] =
      std::to_chars(buf.data(), buf.data() + buf.size(), x, std::chars_format::fixed);
  if (ec != std::errc())
    throw std::runtime_error("cannot format a number");
  return std::string(buf.data(), ptr);
}
}  // namespace

TTrajectory loadTumTrajectory(const std::string& file, EInvalidPose invalid)
{
  std::ifstream in(file, std::ios::binary);
  if (!in)
    throw std::runtime_error(file + ": cannot open");

  TTrajectory trajectory;
  std::string line;
  std::size_t lineNo = 0;
  while (std::getline(in, line))
  {
    ++lineNo;
    // The scripts treat commas and tabs as spaces.
    std::replace(line.begin(), line.end(), ',', ' ');
    std::replace(line.begin(), line.end(), '\t', ' ');
    std::istringstream ss(line);
    std::vector<std::string> tokens;
    for (std::string tok; ss >> tok;)
      tokens.push_back(tok);
    if (tokens.empty() || tokens.front().front() == '#')
      continue;

    if (tokens.size() != 8)
      throw std::runtime_error(
          file + ":" + std::to_string(lineNo) +
          ": expected 8 values (timestamp tx ty tz qx qy qz qw), found " +
          std::to_string(tokens.size()));
    std::array<double, 8> v{};
    bool hasNan = false;
    for (std::size_t k = 0; k < 8; ++k)
    {
      if (!parseNumber(tokens[k], v[k]))
        throw std::runtime_error(
            file + ":" + std::to_string(lineNo) + ": not a number: '" + tokens[k] + "'");
      if (std::isnan(v[k]))
        hasNan = true;
      else if (std::isinf(v[k]))
        throw std::runtime_error(
            file + ":" + std::to_string(lineNo) + ": infinite value '" + tokens[k] + "'");
    }
    // The skips of evaluate_rpe.py's read_trajectory(), or an error.
    const double nq = v[4] * v[4] + v[5] * v[5] + v[6] * v[6] + v[7] * v[7];
    const bool zeroQuaternion = !hasNan && nq < kMinQuaternionNorm2;
    if ((hasNan || zeroQuaternion) && invalid == EInvalidPose::Reject)
      throw std::runtime_error(
          file + ":" + std::to_string(lineNo) +
          (hasNan ? ": NaN value" : ": zero quaternion (no rotation)") +
          " (roi-eval --skip-invalid skips such lines as the benchmark scripts do)");
    if (hasNan || (v[4] == 0 && v[5] == 0 && v[6] == 0 && v[7] == 0))
      continue;

    TPoseStamped p;
    p.timestamp = v[0];
    p.pose = poseFromTum(v);
    trajectory.push_back(std::move(p));
  }
  if (in.bad())
    throw std::runtime_error(file + ": read error");

  // Stable, so a repeated stamp keeps file order (the scripts' dicts keep the last).
  std::stable_sort(
      trajectory.begin(), trajectory.end(),
      [](const TPoseStamped& a, const TPoseStamped& b) { return a.timestamp < b.timestamp; });
  return trajectory;
}

void saveTumTrajectory(
    const std::string& file, const TTrajectory& trajectory, const std::string& headerComment)
{
  namespace fs = std::filesystem;
  const std::string tmp = file + ".tmp" + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out)
      throw std::runtime_error(file + ": cannot write");
    if (!headerComment.empty())
    {
      std::istringstream hc(headerComment);
      for (std::string l; std::getline(hc, l);)
        out << "# " << l << "\n";
    }
    out << "# timestamp tx ty tz qx qy qz qw\n";
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
    out.close();
    if (!out)
    {
      std::error_code ec;
      fs::remove(tmp, ec);
      throw std::runtime_error(file + ": write failed");
    }
  }
  std::error_code ec;
  fs::rename(tmp, file, ec);
  if (ec)
  {
    std::error_code ec2;
    fs::remove(tmp, ec2);
    throw std::runtime_error(file + ": cannot write (" + ec.message() + ")");
  }
}
}  // namespace roislam::io
