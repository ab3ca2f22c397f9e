#include "roislam/io/ObservationConversion.h"

#include <mrpt/core/bits_math.h>
#include <mrpt/img/CImage.h>
#include <mrpt/math/CMatrixFixed.h>
#include <mrpt/system/datetime.h>
#include <roislam/io/CameraAxes.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <opencv2/rgbd.hpp>
#include <stdexcept>
#include <vector>

namespace roislam::io
{
using mrpt::obs::CObservation3DRangeScan;

namespace
{
std::string sizeText(int w, int h)
{
  return std::to_string(w) + "x" + std::to_string(h);
}

// The pinhole part only, not TCamera's operator== (which also compares the
// names, the distortion and the focal length in metres): registerDepth moves
// pixels by the pinhole model alone, and a depth camera named "depth" beside
// one named "rgb" with the same grid needs no registration.
bool sameIntrinsics(const mrpt::img::TCamera& a, const mrpt::img::TCamera& b)
{
  return a.ncols == b.ncols && a.nrows == b.nrows && a.fx() == b.fx() && a.fy() == b.fy() &&
         a.cx() == b.cx() && a.cy() == b.cy();
}

// Metres for every raw 16-bit value, cached per rangeUnits (a frame has 300k
// pixels, the table 65536 entries). rangeUnits is a float, so 1/5000 and 0.001
// are not exact: when it is the inverse of an integer we divide by that
// integer, making metres exactly raw / 5000 (or / 1000) as the TUM folder
// reader computes them.
const std::vector<float>& metresTable(float rangeUnits)
{
  thread_local float cachedUnits = 0;
  thread_local std::vector<float> table;
  if (table.empty() || cachedUnits != rangeUnits)
  {
    const double inverse = 1.0 / double(rangeUnits), inverseInt = std::round(inverse);
    const bool useDivisor = inverseInt >= 1 && std::abs(inverse - inverseInt) < 1e-5 * inverse;
    table.resize(65536);
    for (std::size_t v = 0; v < table.size(); ++v)
      table[v] = static_cast<float>(useDivisor ? v / inverseInt : v * double(rangeUnits));
    cachedUnits = rangeUnits;
  }
  return table;
}
}  // namespace

static const mrpt::poses::CPose3D& opticalToMrptDepthTwist()
{
  // Maps optical coordinates (x right, y down, z forward) into MRPT's depth
  // frame (x forward, y left, z up).
  static const mrpt::poses::CPose3D twist(0, 0, 0, mrpt::DEG2RAD(-90.0), 0, mrpt::DEG2RAD(-90.0));
  return twist;
}

mrpt::poses::CPose3D intensityPoseWrtDepth(const mrpt::poses::CPose3D& depthPoseInColour)
{
  // relativePoseIntensityWRTDepth maps optical-intensity coordinates into the
  // MRPT depth frame: twist (+) the colour optical frame in the depth optical one.
  return opticalToMrptDepthTwist() + (-depthPoseInColour);
}

mrpt::poses::CPose3D depthPoseInColour(const CObservation3DRangeScan& obs)
{
  return (-obs.relativePoseIntensityWRTDepth) + opticalToMrptDepthTwist();
}

// OpenCV's cv::rgbd::registerDepth does the re-projection (z-buffer, nearest
// pixel) and, unlike a pinhole re-projection, projects with the colour
// camera's distortion, so the depth lands on the distorted colour image the
// features are detected in: on a synthetic scene with fr1's colour
// distortion, depth RMSE 17.6 mm against 25.4 mm for a pinhole projection,
// 335 against 1119 pixels off by more than 5 cm (identical without
// distortion). Two defects of OpenCV 4.6's function are worked around here:
// it crashes when the depth grid is larger than the output plane
// (opencv_contrib#3761, e.g. 640x480 depth into 320x240 colour), so the plane
// is made at least as large as the depth grid and cropped; and it marks "no
// depth" with NaN, where our frames use 0.
cv::Mat registerDepthToColour(
    const cv::Mat& depth, const mrpt::img::TCamera& dc, const mrpt::img::TCamera& cc,
    const mrpt::poses::CPose3D& depthOptToColourOpt)
{
  if (depth.type() != CV_32FC1 || depth.cols != static_cast<int>(dc.ncols) ||
      depth.rows != static_cast<int>(dc.nrows))
    throw std::invalid_argument(
        "registerDepthToColour: depth must be CV_32FC1 of the depth camera's " +
        sizeText(dc.ncols, dc.nrows));
  cv::Matx44d Rt;
  const auto H = depthOptToColourOpt.getHomogeneousMatrixVal<mrpt::math::CMatrixDouble44>();
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      Rt(r, c) = H(r, c);
  const cv::Matx33d Kd(dc.fx(), 0, dc.cx(), 0, dc.fy(), dc.cy(), 0, 0, 1);
  const cv::Matx33d Kc(cc.fx(), 0, cc.cx(), 0, cc.fy(), cc.cy(), 0, 0, 1);
  cv::Mat dist(1, static_cast<int>(cc.dist.size()), CV_64F);
  for (std::size_t i = 0; i < cc.dist.size(); ++i)
    dist.at<double>(0, static_cast<int>(i)) = cc.dist[i];
  const int cols = static_cast<int>(cc.ncols), rows = static_cast<int>(cc.nrows);
  const cv::Size plane(std::max(cols, depth.cols), std::max(rows, depth.rows));
  cv::Mat registered;
  cv::rgbd::registerDepth(Kd, Kc, dist, Rt, depth, plane, registered, false);
  cv::Mat out = registered(cv::Rect(0, 0, cols, rows)).clone();
  cv::patchNaNs(out, 0);
  return out;
}

mrpt::poses::CPose3D tumSensorPose()
{
  return -mrpt::poses::CPose3D(0, 0, 0, mrpt::DEG2RAD(-90.0), 0, mrpt::DEG2RAD(-90.0));
}

CObservation3DRangeScan::Ptr observationFromRawDepth(
    const cv::Mat& depthU16, float rangeUnits, const mrpt::img::TCamera& camera, double timestamp)
{
  if (depthU16.type() != CV_16UC1)
    throw std::invalid_argument("observationFromRawDepth: depth must be CV_16UC1");
  if (depthU16.cols != static_cast<int>(camera.ncols) ||
      depthU16.rows != static_cast<int>(camera.nrows))
    throw std::invalid_argument(
        "observationFromRawDepth: depth is " + sizeText(depthU16.cols, depthU16.rows) +
        " but the intrinsics are for " + sizeText(camera.ncols, camera.nrows));
  if (!(rangeUnits > 0))
    throw std::invalid_argument("observationFromRawDepth: rangeUnits <= 0");
  auto obs = CObservation3DRangeScan::Create();
  obs->sensorLabel = "RGBD";
  obs->timestamp = mrpt::Clock::fromDouble(timestamp);
  obs->cameraParams = camera;
  obs->cameraParamsIntensity = camera;
  // The default value, meaning "both cameras coincide" (TUM depth is registered).
  obs->relativePoseIntensityWRTDepth = opticalToMrptDepthTwist();
  obs->sensorPose = tumSensorPose();
  obs->range_is_depth = true;
  obs->rangeUnits = rangeUnits;
  obs->maxRange = static_cast<float>(std::numeric_limits<uint16_t>::max() * double(rangeUnits));
  obs->hasRangeImage = true;
  obs->rangeImage_setSize(depthU16.rows, depthU16.cols);
  for (int r = 0; r < depthU16.rows; ++r)
  {
    const auto* src = depthU16.ptr<uint16_t>(r);
    for (int c = 0; c < depthU16.cols; ++c)
      obs->rangeImage(r, c) = src[c];
  }
  obs->hasIntensityImage = false;
  obs->intensityImageChannel = CObservation3DRangeScan::CH_VISIBLE;
  return obs;
}

CObservation3DRangeScan::Ptr observationFromRawDepth(
    const cv::Mat& depthU16, const TSensorDescription& sensor, double timestamp)
{
  const float rangeUnits = static_cast<float>(1.0 / sensor.depth_scale);
  if (sensor.depth_registered)
    return observationFromRawDepth(depthU16, rangeUnits, sensor.colour, timestamp);
  auto obs = observationFromRawDepth(depthU16, rangeUnits, sensor.depth, timestamp);
  obs->cameraParamsIntensity = sensor.colour;
  obs->relativePoseIntensityWRTDepth = intensityPoseWrtDepth(sensor.depth_pose_in_colour);
  return obs;
}

CObservation3DRangeScan::Ptr frameToObservation(const TRGBDFrame& frame, float rangeUnits)
{
  if (frame.depth.type() != CV_32FC1)
    throw std::invalid_argument("frameToObservation: depth must be CV_32FC1 metres");
  cv::Mat raw(frame.depth.size(), CV_16UC1);
  const double maxRaw = std::numeric_limits<uint16_t>::max();
  for (int r = 0; r < raw.rows; ++r)
    for (int c = 0; c < raw.cols; ++c)
    {
      const double q = std::round(frame.depth.at<float>(r, c) / double(rangeUnits));
      raw.at<uint16_t>(r, c) = (q > 0 && q <= maxRaw) ? static_cast<uint16_t>(q) : 0;
    }
  auto obs = observationFromRawDepth(raw, rangeUnits, frame.camera, frame.timestamp);
  if (frame.rgb.cols != raw.cols || frame.rgb.rows != raw.rows || frame.rgb.type() != CV_8UC3)
    throw std::invalid_argument("frameToObservation: colour must be CV_8UC3 of the depth's size");
  obs->intensityImage = mrpt::img::CImage(frame.rgb, mrpt::img::DEEP_COPY);
  obs->hasIntensityImage = true;
  return obs;
}

namespace
{
/** Throws unless the observation has both images and colour intrinsics. */
void checkObservation(const CObservation3DRangeScan& obs, const std::string& context)
{
  if (!obs.hasRangeImage)
    throw std::runtime_error(context + ": observation has no range image");
  if (!obs.hasIntensityImage)
    throw std::runtime_error(context + ": observation has no intensity (colour) image");
  const auto& cc = obs.cameraParamsIntensity;
  // A negative focal length is an axis running against the image's
  // (ICL-NUIM's fy < 0): the frame gets the flipped images and the camera
  // with positive focal lengths (CameraAxes.h).
  if (cc.ncols == 0 || cc.nrows == 0 || !std::isfinite(cc.fx()) || !std::isfinite(cc.fy()) ||
      cc.fx() == 0 || cc.fy() == 0)
    throw std::runtime_error(context + ": colour intrinsics (cameraParamsIntensity) are not set");
}

/** The colour image as 8-bit BGR of cameraParamsIntensity's size (not yet
 *  flipped). */
cv::Mat colourImage(const CObservation3DRangeScan& obs, const std::string& context)
{
  const auto& cc = obs.cameraParamsIntensity;
  // Colour (external images load lazily here and throw when missing).
  cv::Mat colour;
  try
  {
    colour = obs.intensityImage.asCvMat<cv::Mat>(mrpt::img::DEEP_COPY);
  }
  catch (const std::exception&)
  {
    std::string where;
    if (obs.intensityImage.isExternallyStored())
      where = " '" + obs.intensityImage.getExternalStorageFileAbsolutePath() + "'";
    throw std::runtime_error(context + ": cannot load colour image" + where);
  }
  if (colour.empty())
    throw std::runtime_error(context + ": empty colour image");
  if (colour.depth() != CV_8U)
    throw std::runtime_error(context + ": colour image is not 8-bit");
  cv::Mat rgb;
  if (colour.channels() == 1)
    cv::cvtColor(colour, rgb, cv::COLOR_GRAY2BGR);
  else if (colour.channels() == 4)
    cv::cvtColor(colour, rgb, cv::COLOR_BGRA2BGR);
  else
    rgb = colour;
  if (rgb.cols != static_cast<int>(cc.ncols) || rgb.rows != static_cast<int>(cc.nrows))
    throw std::runtime_error(
        context + ": colour image is " + sizeText(rgb.cols, rgb.rows) +
        " but cameraParamsIntensity is for " + sizeText(cc.ncols, cc.nrows));
  return rgb;
}

}  // namespace

cv::Mat depthMetresOnDepthGrid(const CObservation3DRangeScan& obs, const std::string& context)
{
  const auto& dc = obs.cameraParams;
  const auto& R = obs.rangeImage;
  const int rows = static_cast<int>(R.rows()), cols = static_cast<int>(R.cols());
  if (rows == 0 || cols == 0)
    throw std::runtime_error(context + ": empty range image (" + sizeText(cols, rows) + ")");
  if (cols != static_cast<int>(dc.ncols) || rows != static_cast<int>(dc.nrows))
    throw std::runtime_error(
        context + ": range image is " + sizeText(cols, rows) + " but cameraParams is for " +
        sizeText(dc.ncols, dc.nrows));
  if (!(obs.rangeUnits > 0))
    throw std::runtime_error(context + ": rangeUnits <= 0");
  cv::Mat depth(rows, cols, CV_32FC1);
  const std::vector<float>& metres = metresTable(obs.rangeUnits);
  for (int r = 0; r < rows; ++r)
  {
    auto* dst = depth.ptr<float>(r);
    if (obs.range_is_depth)
    {
      for (int c = 0; c < cols; ++c)
        dst[c] = metres[R(r, c)];
      continue;
    }
    for (int c = 0; c < cols; ++c)
    {
      // Euclidean range along the pixel ray -> depth along the optical axis.
      const double kx = (c - dc.cx()) / dc.fx(), ky = (r - dc.cy()) / dc.fy();
      dst[c] = static_cast<float>(metres[R(r, c)] / std::sqrt(1 + kx * kx + ky * ky));
    }
  }
  return depth;
}

TRGBDFrame observationToFrame(const CObservation3DRangeScan& obs, const std::string& context)
{
  checkObservation(obs, context);
  const auto& dc = obs.cameraParams;
  const auto& cc = obs.cameraParamsIntensity;

  TRGBDFrame f;
  f.timestamp = mrpt::Clock::toDouble(obs.timestamp);
  f.depthTimestamp = f.timestamp;
  f.camera = withPositiveFocalLengths(cc);
  f.rgb = colourImage(obs, context);
  cv::Mat depth = depthMetresOnDepthGrid(obs, context);

  flipToPositiveFocalLengths(f.rgb, cc);
  flipToPositiveFocalLengths(depth, dc);
  if (obs.doDepthAndIntensityCamerasCoincide() && sameIntrinsics(dc, cc))
    f.depth = depth;
  else
  {
    f.depth = registerDepthToColour(
        depth, withPositiveFocalLengths(dc), f.camera, depthPoseInColour(obs));
  }
  return f;
}
}  // namespace roislam::io
