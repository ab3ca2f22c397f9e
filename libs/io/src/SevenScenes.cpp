#include "roislam/io/SevenScenes.h"

#include <mrpt/math/CMatrixFixed.h>
#include <roislam/common/IniRead.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace roislam::io
{
namespace
{
const std::regex& colourName()
{
  static const std::regex re(R"(frame-([0-9]+)\.color\.png)");
  return re;
}

/** The 4x4 matrix of a pose file; nullopt when an entry is not finite.
 *  Throws "<file>: ..." on anything but 4 rows of 4 numbers. */
std::optional<Eigen::Matrix4d> readMatrix(const std::string& file)
{
  std::ifstream in(file);
  if (!in)
    throw std::runtime_error(file + ": cannot open");
  std::vector<double> values;
  std::string token;
  bool finite = true;
  while (in >> token)
  {
    const auto v = common::parseNumber(token);
    if (!v)
      throw std::runtime_error(file + ": not a number: '" + token + "'");
    finite = finite && std::isfinite(*v);
    values.push_back(*v);
  }
  if (in.bad())
    throw std::runtime_error(file + ": read error");
  if (values.size() != 16)
    throw std::runtime_error(
        file + ": expected a 4x4 matrix (16 numbers), got " + std::to_string(values.size()) +
        " numbers");
  if (!finite)
    return std::nullopt;
  Eigen::Matrix4d m;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      m(r, c) = values[static_cast<std::size_t>(4 * r + c)];
  return m;
}

/** Orthonormality and handedness of a rotation read from text (the
 *  dataset's matrices are written with 6-7 significant digits). */
constexpr double kRotationTolerance = 1e-3;
}  // namespace

bool isSevenScenesFolder(const std::string& dir)
{
  const fs::path root(dir);
  std::error_code ec;
  if (!fs::is_directory(root, ec) || fs::exists(root / "rgb.txt", ec))
    return false;
  if (fs::is_regular_file(root / "frame-000000.color.png", ec))
    return true;
  // A sequence cut to start later.
  for (const auto& entry : fs::directory_iterator(root, ec))
    if (std::regex_match(entry.path().filename().string(), colourName()))
      return true;
  return false;
}

std::vector<TSevenScenesFrame> listSevenScenesFrames(const std::string& dir)
{
  const fs::path root = fs::absolute(dir).lexically_normal();
  std::vector<TSevenScenesFrame> frames;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(root, ec))
  {
    const std::string name = entry.path().filename().string();
    std::smatch m;
    if (!std::regex_match(name, m, colourName()))
      continue;
    const std::string stem = "frame-" + m[1].str();
    TSevenScenesFrame f;
    f.number = std::stoul(m[1].str());
    f.colourFile = (root / name).string();
    f.depthFile = (root / (stem + ".depth.png")).string();
    f.poseFile = (root / (stem + ".pose.txt")).string();
    if (!fs::is_regular_file(f.depthFile))
      throw std::runtime_error(f.colourFile + ": no depth image beside it (" + f.depthFile + ")");
    frames.push_back(std::move(f));
  }
  if (ec)
    throw std::runtime_error(root.string() + ": cannot list the folder: " + ec.message());
  if (frames.empty())
    throw std::runtime_error(root.string() + ": no 7-Scenes frame (frame-NNNNNN.color.png)");
  std::sort(
      frames.begin(), frames.end(),
      [](const auto& a, const auto& b) { return a.number < b.number; });
  for (std::size_t i = 1; i < frames.size(); ++i)
    if (frames[i].number == frames[i - 1].number)
      throw std::runtime_error(
          frames[i].colourFile + ": the same frame number as " + frames[i - 1].colourFile);
  return frames;
}

TTrajectory loadSevenScenesGroundTruth(
    const std::vector<TSevenScenesFrame>& frames, double frameRate,
    const mrpt::poses::CPose3D& depthPoseInColour)
{
  if (!(frameRate > 0))
    throw std::invalid_argument("loadSevenScenesGroundTruth: frameRate must be > 0");
  const mrpt::poses::CPose3D colourInDepth = -depthPoseInColour;
  TTrajectory gt;
  for (const auto& f : frames)
  {
    if (!fs::exists(f.poseFile))
      continue;
    const auto m = readMatrix(f.poseFile);
    if (!m)
      continue;
    const Eigen::Matrix3d R = m->topLeftCorner<3, 3>();
    const bool rigid =
        (m->row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() < kRotationTolerance &&
        (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() <
            kRotationTolerance &&
        std::abs(R.determinant() - 1) < kRotationTolerance;
    if (!rigid)
      throw std::runtime_error(
          f.poseFile +
          ": not a rigid transform (rotation not orthonormal with det 1, or last "
          "row not 0 0 0 1)");
    // Re-orthonormalise what was rounded in the text (nearest rotation).
    Eigen::JacobiSVD<Eigen::Matrix3d> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
    mrpt::math::CMatrixDouble33 Rm(Eigen::Matrix3d(svd.matrixU() * svd.matrixV().transpose()));
    mrpt::math::CVectorFixedDouble<3> t;
    for (int i = 0; i < 3; ++i)
      t[i] = (*m)(i, 3);
    const mrpt::poses::CPose3D worldDepth(Rm, t);
    gt.push_back({static_cast<double>(f.number) / frameRate, worldDepth + colourInDepth});
  }
  return gt;
}
}  // namespace roislam::io
