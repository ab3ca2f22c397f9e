#include <mrpt/math/geometry.h>
#include <mrpt/poses/CPose3DQuat.h>
#include <roislam/common/ErrorText.h>
#include <roislam/graphslam/CGravityFrame.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <sstream>

namespace roislam::graphslam
{
namespace
{
using mrpt::math::TVector3D;

double dot(const TVector3D& a, const TVector3D& b)
{
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

double angleDeg(const TVector3D& a, const TVector3D& b)
{
  const double c = std::clamp(dot(a, b) / (a.norm() * b.norm()), -1.0, 1.0);
  return std::acos(c) * 180.0 / M_PI;
}

/** Column k of the rotation of a pose (its axis k in the world). */
TVector3D axis(const mrpt::poses::CPose3D& pose, int k)
{
  const auto R = pose.getRotationMatrix();
  return {R(0, k), R(1, k), R(2, k)};
}

}  // namespace

std::string CGravityFrame::toString(ESource source)
{
  switch (source)
  {
    case ESource::GroundTruth:
      return "ground_truth";
    case ESource::Accelerometer:
      return "accelerometer";
    default:
      return "first_camera";
  }
}

nlohmann::json CGravityFrame::TResult::toJson() const
{
  const mrpt::poses::CPose3DQuat q(toDisplay);
  nlohmann::json j;
  j["up"] = CGravityFrame::toString(source);
  j["estimate_to_display"] = {{"x", q.x()},         {"y", q.y()},         {"z", q.z()},
                              {"qx", q.quat().x()}, {"qy", q.quat().y()}, {"qz", q.quat().z()},
                              {"qw", q.quat().r()}};
  j["accelerometer_samples"] = accelerometerSamples;
  if (accelerometerVsGroundTruthDeg)
    j["accelerometer_vs_ground_truth_deg"] = *accelerometerVsGroundTruthDeg;
  if (!note.empty())
    j["note"] = note;
  return j;
}

mrpt::poses::CPose3D CGravityFrame::levelled(const io::TTrajectory& estimate, const TVector3D& up)
{
  const mrpt::poses::CPose3D first = estimate.empty() ? mrpt::poses::CPose3D() : estimate[0].pose;
  const TVector3D z = up.unitarize();
  // The first camera's view, made level; its right-hand axis when it looks
  // straight up or down.
  TVector3D view = axis(first, 2);
  view = view - z * dot(view, z);
  if (view.norm() < 0.1)
  {
    const TVector3D right = axis(first, 0);
    view = mrpt::math::crossProduct3D(z, right - z * dot(right, z));
  }
  const TVector3D y = view.unitarize();
  const TVector3D x = mrpt::math::crossProduct3D(y, z);
  Eigen::Matrix3d R;  // world -> display: its rows are the display's axes
  R << x.x, x.y, x.z, y.x, y.y, y.z, z.x, z.y, z.z;
  const mrpt::poses::CPose3D rotation(R, mrpt::math::TPoint3D(0, 0, 0));
  const auto origin = first.translation();
  return rotation + mrpt::poses::CPose3D(-origin.x, -origin.y, -origin.z, 0, 0, 0);
}

std::optional<std::pair<TVector3D, std::size_t>> CGravityFrame::upFromAccelerometer(
    const io::TTrajectory& estimate, const io::TAccelerometerLog& accelerometer, std::string& why)
{
  std::vector<double> stamps;
  for (const auto& p : estimate)
    stamps.push_back(p.timestamp);
  if (!std::is_sorted(stamps.begin(), stamps.end()))
  {
    why = "the estimate is not in time order";
    return std::nullopt;
  }
  TVector3D sum(0, 0, 0);
  double magnitude = 0;
  std::size_t n = 0;
  for (const auto& s : accelerometer)
  {
    // The nearest tracked frame (its rotation turns the sample into the world).
    const auto it = std::lower_bound(stamps.begin(), stamps.end(), s.timestamp);
    std::size_t best = stamps.size();
    for (auto cand : {it, it == stamps.begin() ? it : it - 1})
      if (cand != stamps.end() &&
          (best == stamps.size() ||
           std::abs(*cand - s.timestamp) < std::abs(stamps[best] - s.timestamp)))
        best = static_cast<std::size_t>(cand - stamps.begin());
    if (best == stamps.size() || std::abs(stamps[best] - s.timestamp) > kMaxSampleGap)
      continue;
    sum = sum + estimate[best].pose.rotateVector(io::accelerometerToOptical(s.acceleration));
    magnitude += s.acceleration.norm();
    ++n;
  }
  std::ostringstream ss;
  if (n < kMinSamples)
  {
    ss << "accelerometer: " << n << " samples within " << kMaxSampleGap
       << " s of a tracked frame (need " << kMinSamples << ")";
    why = ss.str();
    return std::nullopt;
  }
  const double consistency = sum.norm() / magnitude;
  if (!(consistency >= kMinConsistency))
  {
    ss << "accelerometer: the readings disagree (mean / mean magnitude " << consistency << " < "
       << kMinConsistency << ")";
    why = ss.str();
    return std::nullopt;
  }
  return std::make_pair(sum.unitarize(), n);
}

CGravityFrame::TResult CGravityFrame::choose(
    const io::TTrajectory& estimate,
    const std::optional<mrpt::poses::CPose3D>& groundTruthAlignment,
    const io::TAccelerometerLog& accelerometer)
{
  TResult r;
  std::string why;
  const auto fromAccel =
      accelerometer.empty() ? std::nullopt : upFromAccelerometer(estimate, accelerometer, why);
  if (fromAccel)
    r.accelerometerSamples = fromAccel->second;
  if (groundTruthAlignment)
  {
    r.source = ESource::GroundTruth;
    r.toDisplay = *groundTruthAlignment;
    if (fromAccel)
    {
      // The ground truth's up (+z) seen in the estimate's world.
      const TVector3D gtUp = groundTruthAlignment->inverseRotateVector(TVector3D(0, 0, 1));
      r.accelerometerVsGroundTruthDeg = angleDeg(gtUp, fromAccel->first);
    }
    return r;
  }
  r.note = why;
  if (fromAccel)
  {
    r.source = ESource::Accelerometer;
    r.toDisplay = levelled(estimate, fromAccel->first);
    return r;
  }
  r.source = ESource::FirstCamera;
  const TVector3D down = estimate.empty() ? TVector3D(0, 1, 0) : axis(estimate[0].pose, 1);
  r.toDisplay = levelled(estimate, down * -1.0);
  return r;
}

CGravityFrame::TResult CGravityFrame::choose(
    const io::TTrajectory& estimate,
    const std::optional<mrpt::poses::CPose3D>& groundTruthAlignment,
    const std::optional<std::string>& accelerometerFile)
{
  io::TAccelerometerLog log;
  std::string loadError;
  if (accelerometerFile)
  {
    try
    {
      log = io::loadTumAccelerometer(*accelerometerFile);
    }
    catch (const std::exception& e)
    {
      loadError = common::firstLine(e.what());
    }
  }
  TResult r = choose(estimate, groundTruthAlignment, log);
  if (!loadError.empty())
    r.note = loadError;
  return r;
}
}  // namespace roislam::graphslam
