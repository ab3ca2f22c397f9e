#include "roislam/io/ObservationConversion.h"

#include <mrpt/core/bits_math.h>
#include <mrpt/img/CImage.h>
#include <mrpt/system/datetime.h>

#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
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

// Depth (metres, depth-camera pixels) re-projected into the colour camera with
// a z-buffer; used only for unregistered sensors (e.g. Kinect via freenect).
cv::Mat registerDepth(const cv::Mat& depth, const CObservation3DRangeScan& obs)
{
  const auto& dc = obs.cameraParams;
  const auto& cc = obs.cameraParamsIntensity;
  // relativePoseIntensityWRTDepth maps optical-intensity coordinates into the
  // MRPT depth frame; the fixed twist maps optical-depth into the MRPT depth frame.
  const mrpt::poses::CPose3D twist(0, 0, 0, mrpt::DEG2RAD(-90.0), 0, mrpt::DEG2RAD(-90.0));
  const mrpt::poses::CPose3D depthOptToColourOpt = (-obs.relativePoseIntensityWRTDepth) + twist;
  cv::Mat out(static_cast<int>(cc.nrows), static_cast<int>(cc.ncols), CV_32FC1, cv::Scalar(0));
  for (int r = 0; r < depth.rows; ++r)
    for (int c = 0; c < depth.cols; ++c)
    {
      const float z = depth.at<float>(r, c);
      if (!(z > 0))
        continue;
      const double x = (c - dc.cx()) * z / dc.fx(), y = (r - dc.cy()) * z / dc.fy();
      double X, Y, Z;
      depthOptToColourOpt.composePoint(x, y, z, X, Y, Z);
      if (!(Z > 0))
        continue;
      const int u = static_cast<int>(std::lround(cc.fx() * X / Z + cc.cx()));
      const int v = static_cast<int>(std::lround(cc.fy() * Y / Z + cc.cy()));
      if (u < 0 || v < 0 || u >= out.cols || v >= out.rows)
        continue;
      float& dst = out.at<float>(v, u);
      if (dst == 0 || Z < dst)
        dst = static_cast<float>(Z);
    }
  return out;
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
  obs->relativePoseIntensityWRTDepth =
      mrpt::poses::CPose3D(0, 0, 0, mrpt::DEG2RAD(-90.0), 0, mrpt::DEG2RAD(-90.0));
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

TRGBDFrame observationToFrame(const CObservation3DRangeScan& obs, const std::string& context)
{
  if (!obs.hasRangeImage)
    throw std::runtime_error(context + ": observation has no range image");
  if (!obs.hasIntensityImage)
    throw std::runtime_error(context + ": observation has no intensity (colour) image");
  const auto& dc = obs.cameraParams;
  const auto& cc = obs.cameraParamsIntensity;
  if (cc.ncols == 0 || cc.nrows == 0 || !(cc.fx() > 0) || !(cc.fy() > 0))
    throw std::runtime_error(context + ": colour intrinsics (cameraParamsIntensity) are not set");

  TRGBDFrame f;
  f.timestamp = mrpt::Clock::toDouble(obs.timestamp);
  f.depthTimestamp = f.timestamp;
  f.camera = cc;

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
  if (colour.channels() == 1)
    cv::cvtColor(colour, f.rgb, cv::COLOR_GRAY2BGR);
  else if (colour.channels() == 4)
    cv::cvtColor(colour, f.rgb, cv::COLOR_BGRA2BGR);
  else
    f.rgb = colour;
  if (f.rgb.cols != static_cast<int>(cc.ncols) || f.rgb.rows != static_cast<int>(cc.nrows))
    throw std::runtime_error(
        context + ": colour image is " + sizeText(f.rgb.cols, f.rgb.rows) +
        " but cameraParamsIntensity is for " + sizeText(cc.ncols, cc.nrows));

  // Depth in metres on the depth camera's pixel grid.
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

  if (obs.doDepthAndIntensityCamerasCoincide() && sameIntrinsics(dc, cc))
    f.depth = depth;
  else
    f.depth = registerDepth(depth, obs);
  return f;
}
}  // namespace roislam::io
