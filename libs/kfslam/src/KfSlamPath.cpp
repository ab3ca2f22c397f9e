#include "roislam/kfslam/KfSlamPath.h"

#include <mrpt/poses/CPose3DQuat.h>
#include <roislam/common/TextFiles.h>

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace roislam::kfslam
{
using mrpt::poses::CPose3D;

std::vector<CPose3D> worldRobotPath(const TKfSlamRun& run, const std::vector<CPose3D>& odometry)
{
  if (odometry.size() != run.robotPath.size())
    throw std::invalid_argument(
        "kf-slam path has " + std::to_string(run.robotPath.size()) + " steps, the odometry " +
        std::to_string(odometry.size()));
  if (!run.firstLandmarkStep)
    return odometry;  // the filter never moved the robot
  const std::size_t k0 = *run.firstLandmarkStep;
  std::vector<CPose3D> out(odometry.begin(), odometry.begin() + k0);
  for (std::size_t k = k0; k < run.robotPath.size(); ++k)
    out.push_back(odometry[k0] + run.robotPath[k]);
  return out;
}

io::TTrajectory cameraTrajectory(
    const std::vector<CPose3D>& robotPath, const std::vector<double>& stamps,
    const COdometryIncrements& frames)
{
  io::TTrajectory t;
  for (std::size_t k = 0; k < robotPath.size() && k < stamps.size(); ++k)
    t.push_back({stamps[k], frames.cameraPose(robotPath[k])});
  return t;
}

std::map<int64_t, mrpt::math::TPoint3D> referenceLandmarks(
    const std::map<int64_t, TFirstSight>& firstSights, const io::TTrajectory& gt, double k0Stamp,
    const COdometryIncrements& frames)
{
  std::map<int64_t, mrpt::math::TPoint3D> out;
  const auto origin = io::poseAt(gt, k0Stamp, 0.02);
  if (!origin)
    return out;
  const CPose3D filterFrame = frames.robotPose(*origin);
  for (const auto& [id, s] : firstSights)
    if (const auto g = io::poseAt(gt, s.timestamp, 0.02))
      out[id] = filterFrame.inverseComposePoint(g->composePoint(s.optical));
  return out;
}

std::optional<double> meanLandmarkError(
    const std::map<int64_t, mrpt::math::TPoint3D>& map,
    const std::map<int64_t, mrpt::math::TPoint3D>& reference)
{
  double sum = 0;
  std::size_t n = 0;
  for (const auto& [id, p] : map)
    if (const auto it = reference.find(id); it != reference.end())
    {
      sum += (p - it->second).norm();
      ++n;
    }
  return n ? std::optional<double>(sum / n) : std::nullopt;
}

void saveKfSlamLandmarks(
    const std::string& file, const std::map<int64_t, mrpt::math::TPoint3D>& landmarks)
{
  std::ostringstream os;
  os << std::setprecision(9);
  for (const auto& [id, p] : landmarks)
    os << p.x << ' ' << p.y << ' ' << p.z << " 0 0 0 " << id << '\n';
  common::writeFileAtomically(file, os.str());
}

std::vector<CPose3D> loadKfSlamRobotPoses(const std::string& dir)
{
  std::vector<CPose3D> out;
  for (std::size_t step = 0;; ++step)
  {
    std::ostringstream name;
    name << "robot_pose_" << std::setw(5) << std::setfill('0') << step << ".txt";
    const fs::path file = fs::path(dir) / name.str();
    std::ifstream in(file);
    if (!in)
      break;
    double v[7];
    for (double& x : v)
      if (!(in >> x))
        throw std::runtime_error(file.string() + ": expected x y z qr qx qy qz");
    out.emplace_back(CPose3D(mrpt::poses::CPose3DQuat(
        v[0], v[1], v[2], mrpt::math::CQuaternionDouble(v[3], v[4], v[5], v[6]))));
  }
  if (out.empty())
    throw std::runtime_error(dir + ": no robot_pose_00000.txt (kf-slam's path)");
  return out;
}
}  // namespace roislam::kfslam
