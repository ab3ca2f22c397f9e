#include "roislam/geometry/KeypointLifting.h"

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <stdexcept>

namespace roislam::geometry
{
float depthByRule(const cv::Mat& depth, int u, int v, const TDepthRule& rule)
{
  // The 3x3 test needs the neighbours: the outermost rows and columns have none.
  if (u < 1 || v < 1 || u >= depth.cols - 1 || v >= depth.rows - 1)
    return 0;
  const float z = depth.at<float>(v, u);
  if (!(z >= rule.min_depth_m && z <= rule.max_depth_m))
    return 0;
  if (rule.depth_discontinuity_m > 0)
  {
    float lo = z, hi = z;
    for (int dv = -1; dv <= 1; ++dv)
      for (int du = -1; du <= 1; ++du)
      {
        const float zz = depth.at<float>(v + dv, u + du);
        lo = std::min(lo, zz);
        hi = std::max(hi, zz);
      }
    if (lo <= 0 || hi - lo > rule.depth_discontinuity_m * z)
      return 0;
  }
  return z;
}

TLiftedPixels liftPixels(
    const std::vector<cv::Point2f>& pixels, const cv::Mat& depth, cv::InputArray K,
    cv::InputArray dist, const TDepthRule& rule)
{
  if (depth.type() != CV_32FC1)
    throw std::invalid_argument("liftPixels: depth must be CV_32FC1 metres");
  TLiftedPixels out;
  if (pixels.empty())
    return out;
  cv::undistortPoints(pixels, out.undistorted, K, dist, cv::noArray(), K);
  out.z.assign(pixels.size(), 0.0F);
  for (std::size_t i = 0; i < pixels.size(); ++i)
  {
    const int u = static_cast<int>(std::lround(pixels[i].x));
    const int v = static_cast<int>(std::lround(pixels[i].y));
    const float z = depthByRule(depth, u, v, rule);
    if (z > 0)
    {
      out.z[i] = z;
      out.valid.push_back(static_cast<int>(i));
    }
  }
  return out;
}
}  // namespace roislam::geometry
