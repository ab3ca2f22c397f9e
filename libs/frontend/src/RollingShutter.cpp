#include "RollingShutter.h"

#include <roislam/geometry/RollingShutterMotion.h>
#include <roislam/geometry/Rotation.h>

#include <cmath>
#include <opencv2/calib3d.hpp>

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
  return geometry::carryToReferenceRow(X, rate.omega, rate.linear, s);
}

void rectifyRollingShutter(
    TLiftedFeatures& lifted, const TCameraRate& rate, double readout_s, const TPinhole& pinhole)
{
  lifted.undistorted = lifted.rawUndistorted;
  lifted.z = lifted.rawZ;
  lifted.rate = rate;
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

void alignDepthTime(
    TLiftedFeatures& lifted, const cv::Mat& depth, const cv::Mat& K, const cv::Mat& dist,
    const geometry::TDepthRule& rule, const TPinhole& pinhole, const TCameraRate& rate, double dt,
    bool dropUnread)
{
  if (dt == 0 || !std::isfinite(dt) || rate.isZero())
  {
    for (int i : lifted.valid)
      lifted.rawZ[static_cast<std::size_t>(i)] = lifted.readZ[static_cast<std::size_t>(i)];
    lifted.z = lifted.rawZ;
    return;
  }
  // carryToReferenceRow(X, omega, v, dt) takes a point seen dt after the
  // colour image into the colour's camera; its inverse finds where the
  // colour's point was at the depth's time.
  const Eigen::Matrix3d R = geometry::expSO3(rate.omega * dt);
  const Eigen::Vector3d t = rate.linear * dt;
  std::vector<cv::Point3f> atDepthTime;
  std::vector<int> idx;
  atDepthTime.reserve(lifted.valid.size());
  idx.reserve(lifted.valid.size());
  for (int i : lifted.valid)
  {
    const auto k = static_cast<std::size_t>(i);
    const Eigen::Vector3d X = pinhole.backProject(lifted.rawUndistorted[k], lifted.readZ[k]);
    const Eigen::Vector3d Xd = R.transpose() * (X - t);
    if (!(Xd.z() > 0))
      continue;
    atDepthTime.emplace_back(
        static_cast<float>(Xd.x()), static_cast<float>(Xd.y()), static_cast<float>(Xd.z()));
    idx.push_back(i);
  }
  // The depth image is registered to the distorted colour image: read it at
  // the distorted pixel of that point.
  std::vector<cv::Point2f> pixels;
  if (!atDepthTime.empty())
  {
    const cv::Mat zero = cv::Mat::zeros(3, 1, CV_64F);
    cv::projectPoints(atDepthTime, zero, zero, K, dist, pixels);
  }
  const geometry::TLiftedPixels again = geometry::liftPixels(pixels, depth, K, dist, rule);
  std::vector<char> read(lifted.rawZ.size(), 0);
  for (int j : again.valid)
  {
    const auto jj = static_cast<std::size_t>(j);
    const auto k = static_cast<std::size_t>(idx[jj]);
    const Eigen::Vector3d X = R * pinhole.backProject(again.undistorted[jj], again.z[jj]) + t;
    if (!(X.z() > 0))
      continue;
    // The colour's pixel stays: it measured the ray; the depth measured how
    // far along it the point lies.
    lifted.rawZ[k] = static_cast<float>(X.z());
    read[k] = 1;
  }
  if (dropUnread)
  {
    std::vector<int> valid;
    valid.reserve(lifted.valid.size());
    for (int i : lifted.valid)
      if (read[static_cast<std::size_t>(i)])
        valid.push_back(i);
    lifted.valid = std::move(valid);
  }
  lifted.z = lifted.rawZ;
}

TLiftedFeatures liftAtColourTime(
    const features::TFeatureSet& set, const cv::Mat& depth, const cv::Mat& K, const cv::Mat& dist,
    const TPinhole& pinhole, const CRgbdOdometry::TOptions& o, const TCameraRate& rate, double dt)
{
  TLiftedFeatures lifted = liftFeatures(set, depth, K, dist, o);
  if (dt != 0)
    alignDepthTime(lifted, depth, K, dist, depthRule(o), pinhole, rate, dt, true);
  return lifted;
}

void realignDepthTime(
    TLiftedFeatures& lifted, const cv::Mat& depth, const cv::Mat& K, const cv::Mat& dist,
    const TPinhole& pinhole, const CRgbdOdometry::TOptions& o, const TCameraRate& rate, double dt)
{
  if (dt != 0)
    alignDepthTime(lifted, depth, K, dist, depthRule(o), pinhole, rate, dt, false);
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
  setKeyframeRate(k, rate);
}
}  // namespace roislam::frontend::detail
