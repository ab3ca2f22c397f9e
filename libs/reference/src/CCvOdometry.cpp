#include "roislam/reference/CCvOdometry.h"

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/math/CMatrixFixed.h>
#include <roislam/common/IniErrors.h>
#include <roislam/common/IniRead.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/rgbd.hpp>
#include <stdexcept>

namespace roislam::reference
{
namespace
{
bool hasDistortion(const mrpt::img::TCamera& c)
{
  if (c.distortion == mrpt::img::DistortionModel::none)
    return false;
  for (double d : c.dist)
    if (d != 0)
      return true;
  return false;
}

cv::Mat cameraMatrix(const mrpt::img::TCamera& c)
{
  return (cv::Mat_<double>(3, 3) << c.fx(), 0, c.cx(), 0, c.fy(), c.cy(), 0, 0, 1);
}
}  // namespace

void CCvOdometry::TOptions::validate(const std::string& section) const
{
  if (method != "rgbd" && method != "icp" && method != "rgbdicp")
    common::throwBadIniKey(
        section, "method", "must be rgbd, icp or rgbdicp (got '" + method + "')");
  common::require(min_depth >= 0, section, "min_depth", min_depth, ">= 0 m");
  common::require(max_depth > min_depth, section, "max_depth", max_depth, "> min_depth");
  common::require(max_depth_diff > 0, section, "max_depth_diff", max_depth_diff, "> 0 m");
  common::require(
      max_points_part > 0 && max_points_part <= 1, section, "max_points_part", max_points_part,
      "in (0, 1]");
}

void CCvOdometry::TOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section)
{
  method = common::readString(cfg, section, "method", method);
  min_depth = common::readDouble(cfg, section, "min_depth", min_depth);
  max_depth = common::readDouble(cfg, section, "max_depth", max_depth);
  max_depth_diff = common::readDouble(cfg, section, "max_depth_diff", max_depth_diff);
  max_points_part = common::readDouble(cfg, section, "max_points_part", max_points_part);
  undistort = common::readBool(cfg, section, "undistort", undistort);
  validate(section);
}

void CCvOdometry::TOptions::saveToConfigFile(
    mrpt::config::CConfigFileBase& cfg, const std::string& section) const
{
  cfg.write(section, "method", method);
  cfg.write(section, "min_depth", min_depth);
  cfg.write(section, "max_depth", max_depth);
  cfg.write(section, "max_depth_diff", max_depth_diff);
  cfg.write(section, "max_points_part", max_points_part);
  cfg.write(section, "undistort", undistort);
}

struct CCvOdometry::TImpl
{
  mrpt::img::TCamera camera;
  cv::Ptr<cv::rgbd::Odometry> odometry;
  bool undistort = false;
  cv::Mat mapX, mapY;  //!< undistortion maps onto the same camera matrix
  cv::Ptr<cv::rgbd::OdometryFrame> previous;
  mrpt::poses::CPose3D pose;
};

std::string CCvOdometry::className(const std::string& method)
{
  if (method == "rgbd")
    return "RgbdOdometry";
  if (method == "icp")
    return "ICPOdometry";
  if (method == "rgbdicp")
    return "RgbdICPOdometry";
  throw std::invalid_argument("unknown cv::rgbd odometry '" + method + "'");
}

CCvOdometry::CCvOdometry(const TOptions& options, const mrpt::img::TCamera& camera)
    : m_options(options), m_impl(std::make_unique<TImpl>())
{
  m_options.validate();
  if (camera.ncols == 0 || camera.nrows == 0 || !(camera.fx() > 0) || !(camera.fy() > 0))
    throw std::invalid_argument("CCvOdometry: camera needs a positive size and focal length");
  m_impl->camera = camera;
  const cv::Mat K = cameraMatrix(camera);
  const auto minD = static_cast<float>(m_options.min_depth);
  const auto maxD = static_cast<float>(m_options.max_depth);
  const auto diff = static_cast<float>(m_options.max_depth_diff);
  const auto part = static_cast<float>(m_options.max_points_part);
  if (m_options.method == "rgbd")
    m_impl->odometry = cv::rgbd::RgbdOdometry::create(K, minD, maxD, diff, {}, {}, part);
  else if (m_options.method == "icp")
    m_impl->odometry = cv::rgbd::ICPOdometry::create(K, minD, maxD, diff, part);
  else
    m_impl->odometry = cv::rgbd::RgbdICPOdometry::create(K, minD, maxD, diff, part);
  m_impl->undistort = m_options.undistort && hasDistortion(camera);
  if (m_impl->undistort)
  {
    const cv::Mat D(1, 5, CV_64F, const_cast<double*>(camera.dist.data()));
    cv::initUndistortRectifyMap(
        K, D, cv::Mat(), K, cv::Size(camera.ncols, camera.nrows), CV_32FC1, m_impl->mapX,
        m_impl->mapY);
  }
}

CCvOdometry::~CCvOdometry() = default;

CCvOdometry::TStep CCvOdometry::process(const io::TRGBDFrame& frame)
{
  const auto& cam = m_impl->camera;
  if (frame.rgb.cols != static_cast<int>(cam.ncols) ||
      frame.rgb.rows != static_cast<int>(cam.nrows) || frame.depth.size() != frame.rgb.size() ||
      frame.depth.type() != CV_32FC1)
    throw std::invalid_argument(
        "CCvOdometry: frame " + std::to_string(frame.index) +
        ": colour and depth (CV_32FC1) must match the camera's size");
  const auto start = std::chrono::steady_clock::now();
  cv::Mat grey = frame.grey(), depth = frame.depth.clone();
  if (m_impl->undistort)
  {
    cv::remap(grey, grey, m_impl->mapX, m_impl->mapY, cv::INTER_LINEAR);
    cv::remap(depth, depth, m_impl->mapX, m_impl->mapY, cv::INTER_NEAREST);
  }
  // OpenCV's odometries take missing depth as NaN (as its own TUM sample does).
  depth.setTo(std::numeric_limits<float>::quiet_NaN(), depth == 0);
  cv::Ptr<cv::rgbd::OdometryFrame> current = cv::rgbd::OdometryFrame::create(grey, depth);

  TStep step;
  if (m_impl->previous)
  {
    // src = this frame, dst = the previous one: Rt maps this camera's points
    // into the previous camera, i.e. it is the pose of this frame in the previous.
    cv::Mat Rt;
    step.tracked = m_impl->odometry->compute(current, m_impl->previous, Rt);
    if (step.tracked)
    {
      mrpt::math::CMatrixDouble44 T;
      for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c)
          T(r, c) = Rt.at<double>(r, c);
      m_impl->pose = m_impl->pose + mrpt::poses::CPose3D(T);
    }
  }
  else
    m_impl->odometry->prepareFrameCache(current, cv::rgbd::OdometryFrame::CACHE_ALL);
  m_impl->previous = current;
  step.pose = m_impl->pose;
  step.ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return step;
}
}  // namespace roislam::reference
