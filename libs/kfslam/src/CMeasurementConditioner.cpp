#include "roislam/kfslam/CMeasurementConditioner.h"

#include <mrpt/math/distributions.h>
#include <mrpt/math/wrap2pi.h>
#include <roislam/geometry/RollingShutterMotion.h>
#include <roislam/geometry/Rotation.h>

#include <algorithm>
#include <cmath>

namespace roislam::kfslam
{
namespace
{
// A hand-held camera does not turn faster or move faster than this; a rate
// beyond it comes from a failed registration and is not applied (the front
// end's bound, RollingShutter.cpp).
constexpr double kMaxTurnRadS = 2 * M_PI, kMaxSpeedMS = 3.0;

/** A measurement (MRPT's camera frame: x forward, y left, z up) as an
 *  optical-frame point (x right, y down, z forward). */
mrpt::math::TPoint3D opticalPoint(const mrpt::obs::CObservationBearingRange::TMeasurement& m)
{
  const double r = m.range, yaw = m.yaw, pitch = m.pitch;
  return {
      -r * std::sin(yaw) * std::cos(pitch), r * std::sin(pitch),
      r * std::cos(yaw) * std::cos(pitch)};
}

mrpt::math::TPoint3D medianPoint(std::vector<mrpt::math::TPoint3D> points)
{
  mrpt::math::TPoint3D out;
  for (int k = 0; k < 3; ++k)
  {
    const auto mid = points.begin() + static_cast<std::ptrdiff_t>(points.size() / 2);
    std::nth_element(
        points.begin(), mid, points.end(),
        [k](const auto& a, const auto& b) { return a[k] < b[k]; });
    out[k] = (*mid)[k];
  }
  return out;
}
}  // namespace

CMeasurementConditioner::CMeasurementConditioner(
    bool rectify, double readoutMs, double intervalS, double gateProbability)
    : m_rectify(rectify && readoutMs != 0),
      m_readoutS(readoutMs / 1000.0),
      m_intervalS(intervalS),
      m_gateChi2(gateProbability > 0 ? mrpt::math::chi2inv(gateProbability, 3) : 0)
{
}

bool CMeasurementConditioner::withinGate(
    const mrpt::obs::CObservationBearingRange::TMeasurement& m,
    const mrpt::poses::CPose3D& cameraPose, const TTrack& track) const
{
  const auto& seen = track.points;
  // The landmark's reference point as this camera would measure it.
  const auto q = cameraPose.inverseComposePoint(medianPoint(seen));
  double range, yaw, pitch;
  mrpt::poses::CPose3D().sphericalCoordinates({q.z, -q.x, -q.y}, range, yaw, pitch);
  const Eigen::Vector3d nu(
      m.range - range, mrpt::math::wrapToPi(m.yaw - yaw), mrpt::math::wrapToPi(m.pitch - pitch));
  // The measurement's own covariance, and the reference's: a median of n
  // measurements as noisy, taken as their mean (variance / n).
  Eigen::Matrix3d c;
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k)
      c(r, k) = m.covariance(r, k);
  const double n = static_cast<double>(seen.size());
  c *= 1.0 + 1.0 / n;
  // The odometry's drift since the reference's sightings (their mean epoch):
  // in range, and in bearing from the translation at this range and the turn.
  const double driftT = std::max(0.0, m_driftT - track.driftTSum / n);
  const double driftR = std::max(0.0, m_driftR - track.driftRSum / n);
  c(0, 0) += driftT;
  c(1, 1) += driftT / (range * range) + driftR;
  c(2, 2) += driftT / (range * range) + driftR;
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(c);
  if (ldlt.info() != Eigen::Success || !(c.determinant() > 0))
    return true;
  return nu.dot(ldlt.solve(nu)) <= m_gateChi2;
}

void CMeasurementConditioner::rectify(
    mrpt::obs::CObservationBearingRange::TMeasurement& m, const mrpt::img::TCamera& camera,
    double readoutS, const mrpt::math::TPoint3D& omega, const mrpt::math::TPoint3D& v)
{
  const auto o = opticalPoint(m);
  const Eigen::Vector3d X(o.x, o.y, o.z);
  if (!(X.z() > 0) || camera.nrows <= 0)
    return;
  const double row = camera.fy() * X.y() / X.z() + camera.cy();
  const double s = (row / camera.nrows - 0.5) * readoutS;
  const Eigen::Vector3d w(omega.x, omega.y, omega.z), lin(v.x, v.y, v.z);
  const Eigen::Vector3d Y = geometry::carryToReferenceRow(X, w, lin, s);
  if (!(Y.z() > 0))
    return;
  // Back to range / yaw / pitch (CPose3D::sphericalCoordinates of (z, -x, -y)).
  const double range = Y.norm();
  m.range = static_cast<float>(range);
  m.yaw = static_cast<float>(std::atan2(-Y.x(), Y.z()));
  m.pitch = static_cast<float>(-std::asin(-Y.y() / range));
}

void CMeasurementConditioner::addMotion(const mrpt::math::CMatrixDouble66& covariance)
{
  m_driftT += (covariance(0, 0) + covariance(1, 1) + covariance(2, 2)) / 3;
  m_driftR += (covariance(3, 3) + covariance(4, 4) + covariance(5, 5)) / 3;
}

mrpt::obs::CObservationBearingRange CMeasurementConditioner::condition(
    const mrpt::obs::CObservationBearingRange& observation, const mrpt::img::TCamera& camera,
    double stamp, const std::optional<mrpt::poses::CPose3D>& cameraPose)
{
  mrpt::obs::CObservationBearingRange out = observation;
  out.sensedData.clear();
  std::optional<std::pair<mrpt::math::TPoint3D, mrpt::math::TPoint3D>> rate;
  if (m_rectify && cameraPose && m_previous && stamp > m_previous->first)
  {
    const double dt = stamp - m_previous->first;
    const mrpt::poses::CPose3D motion = *cameraPose - m_previous->second;
    const Eigen::Vector3d w = geometry::logSO3(motion.getRotationMatrix().asEigen()) / dt;
    const Eigen::Vector3d v = Eigen::Vector3d(motion.x(), motion.y(), motion.z()) / dt;
    if (w.allFinite() && v.allFinite() && w.norm() <= kMaxTurnRadS && v.norm() <= kMaxSpeedMS)
      rate.emplace(
          mrpt::math::TPoint3D(w.x(), w.y(), w.z()), mrpt::math::TPoint3D(v.x(), v.y(), v.z()));
  }
  if (cameraPose)
    m_previous.emplace(stamp, *cameraPose);
  else
    m_previous.reset();

  for (auto m : observation.sensedData)
  {
    const auto last = m_lastMeasured.find(m.landmarkID);
    if (last != m_lastMeasured.end() && stamp - last->second < m_intervalS)
    {
      ++m_skipped;
      continue;
    }
    if (rate)
      rectify(m, camera, m_readoutS, rate->first, rate->second);
    if (m_gateChi2 > 0 && cameraPose)
    {
      auto& track = m_tracks[m.landmarkID];
      if (!track.points.empty() && !withinGate(m, *cameraPose, track))
      {
        ++m_gated;
        continue;
      }
      track.points.push_back(cameraPose->composePoint(opticalPoint(m)));
      track.driftTSum += m_driftT;
      track.driftRSum += m_driftR;
    }
    m_lastMeasured[m.landmarkID] = stamp;
    out.sensedData.push_back(m);
  }
  return out;
}
}  // namespace roislam::kfslam
