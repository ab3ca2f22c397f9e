#include "roislam/sim/CCameraPath.h"

#include <mrpt/core/bits_math.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace roislam::sim
{
namespace
{
// Optical frame (+Z forward, +X right, +Y down) relative to a body frame
// (x forward, y left, z up).
const mrpt::poses::CPose3D kBodyToOptical(0, 0, 0, -M_PI / 2, 0, -M_PI / 2);
constexpr int kSpeedSamples = 2000;
}  // namespace

CCameraPath::CCameraPath(const TParams& params, double duration) : m_p(params), m_duration(duration)
{
  if (!(duration > 0))
    throw std::invalid_argument("camera path duration must be > 0");
  if (!(params.maxLinearSpeed > 0) || !(params.maxAngularSpeedDeg > 0))
    throw std::invalid_argument("camera path speed limits must be > 0");
  // Position and angles are (nearly) linear in their scale factors, so a few
  // proportional corrections with a small margin converge.
  for (int it = 0; it < 20; ++it)
  {
    const double v = maxLinearSpeed(), w = maxAngularSpeedDeg();
    const bool okV = v <= m_p.maxLinearSpeed, okW = w <= m_p.maxAngularSpeedDeg;
    if (okV && okW)
      break;
    if (!okV)
      m_linScale *= 0.98 * m_p.maxLinearSpeed / v;
    if (!okW)
      m_angScale *= 0.98 * m_p.maxAngularSpeedDeg / w;
  }
}

mrpt::poses::CPose3D CCameraPath::opticalPoseAt(double t) const
{
  const double phi = 2 * M_PI * t / m_duration;
  const double A = m_p.translationAmplitude * m_linScale;
  // Ellipse in the horizontal plane (right first, then forward) plus a bob.
  const double dx = 0.5 * A * (1 - std::cos(phi));
  const double dy = -A * std::sin(phi);
  const double dz = 0.25 * A * std::sin(2 * phi);
  const double yaw0 = mrpt::DEG2RAD(m_p.yawDeg);
  const double x = m_p.x + std::cos(yaw0) * dx - std::sin(yaw0) * dy;
  const double y = m_p.y + std::sin(yaw0) * dx + std::cos(yaw0) * dy;
  // Yaw turns back towards the loop centre; pitch and roll wobble at other phases.
  const double s = m_angScale;
  const double yaw = yaw0 + s * mrpt::DEG2RAD(m_p.yawAmplitudeDeg) * std::sin(phi);
  const double pitch = mrpt::DEG2RAD(m_p.pitchDeg) +
                       s * mrpt::DEG2RAD(m_p.pitchAmplitudeDeg) * std::sin(2 * phi + 0.7);
  const double roll =
      mrpt::DEG2RAD(m_p.rollDeg) + s * mrpt::DEG2RAD(m_p.rollAmplitudeDeg) * std::sin(phi + 1.3);
  return mrpt::poses::CPose3D(x, y, m_p.z + dz, yaw, pitch, roll) + kBodyToOptical;
}

double CCameraPath::maxLinearSpeed() const
{
  const double dt = m_duration / kSpeedSamples;
  double best = 0;
  for (int i = 0; i < kSpeedSamples; ++i)
  {
    const auto a = opticalPoseAt(i * dt), b = opticalPoseAt((i + 1) * dt);
    best = std::max(best, (b.translation() - a.translation()).norm() / dt);
  }
  return best;
}

double CCameraPath::maxAngularSpeedDeg() const
{
  const double dt = m_duration / kSpeedSamples;
  double best = 0;
  for (int i = 0; i < kSpeedSamples; ++i)
  {
    const auto a = opticalPoseAt(i * dt), b = opticalPoseAt((i + 1) * dt);
    const auto R = (b - a).getRotationMatrix();
    const double c = std::clamp((R(0, 0) + R(1, 1) + R(2, 2) - 1) / 2, -1.0, 1.0);
    best = std::max(best, mrpt::RAD2DEG(std::acos(c)) / dt);
  }
  return best;
}
}  // namespace roislam::sim
