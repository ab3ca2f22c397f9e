#include "RollingShutter.h"

#include <roislam/geometry/Rotation.h>

#include <cmath>

namespace roislam::frontend::detail
{
// Beyond a full turn or 3 m per second (no hand-held camera) the motion is
// taken as a failed registration: zero.
TCameraRate cameraRate(const mrpt::poses::CPose3D& motion, double dt)
{
  constexpr double maxTurn = 2 * M_PI, maxSpeed = 3.0;
  TCameraRate r;
  if (!(dt > 0))
    return r;
  r.omega = geometry::logSO3(motion.getRotationMatrix().asEigen()) / dt;
  r.linear = Eigen::Vector3d(motion.x(), motion.y(), motion.z()) / dt;
  if (!r.omega.allFinite() || !r.linear.allFinite() || r.omega.norm() > maxTurn ||
      r.linear.norm() > maxSpeed)
    return {};
  return r;
}

Eigen::Vector3d rectifyPoint(
    const cv::Point2f& rawPixel, double rawZ, double s, const TCameraRate& rate,
    const TPinhole& pinhole)
{
  const Eigen::Vector3d X = pinhole.backProject(rawPixel, rawZ);
  return geometry::expSO3(rate.omega * s) * X + rate.linear * s;
}

void rectifyRollingShutter(
    TLiftedFeatures& lifted, const TCameraRate& rate, double readout_s, const TPinhole& pinhole)
{
  lifted.undistorted = lifted.rawUndistorted;
  lifted.z = lifted.rawZ;
  if (readout_s == 0 || rate.isZero())
    return;
  for (int i : lifted.valid)
  {
    const auto k = static_cast<std::size_t>(i);
    const Eigen::Vector3d X = rectifyPoint(
        lifted.rawUndistorted[k], lifted.rawZ[k], lifted.rowFraction[k] * readout_s, rate, pinhole);
    // A few milliseconds of motion cannot put a point behind the camera; the
    // guard only keeps a corrupt rate from producing NaNs.
    if (!(X.z() > 0))
      continue;
    lifted.z[k] = static_cast<float>(X.z());
    lifted.undistorted[k] = pinhole.project(X);
  }
}

TUncorrectedKeyframe uncorrectedKeyframe(
    std::size_t id, const TLiftedFeatures& lifted, const std::vector<int>& idx)
{
  TUncorrectedKeyframe u;
  u.id = id;
  for (int i : idx)
  {
    const auto k = static_cast<std::size_t>(i);
    u.rawPixels.push_back(lifted.rawUndistorted[k]);
    u.rawZ.push_back(lifted.rawZ[k]);
    u.rowFraction.push_back(lifted.rowFraction[k]);
  }
  return u;
}

void correctKeyframe(
    TKeyframe& k, const TUncorrectedKeyframe& u, const TCameraRate& rate, double readout_s,
    const TPinhole& pinhole)
{
  for (std::size_t j = 0; j < k.points.size() && j < u.rawPixels.size(); ++j)
  {
    const Eigen::Vector3d X =
        rectifyPoint(u.rawPixels[j], u.rawZ[j], u.rowFraction[j] * readout_s, rate, pinhole);
    if (!(X.z() > 0))  // as in rectifyRollingShutter
      continue;
    k.points[j] = mrpt::math::TPoint3D(X.x(), X.y(), X.z());
    k.pixels[j] = pinhole.project(X);
  }
}
}  // namespace roislam::frontend::detail
