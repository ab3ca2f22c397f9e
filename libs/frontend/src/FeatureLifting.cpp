#include "FeatureLifting.h"

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>

namespace roislam::frontend::detail
{
TLiftedFeatures liftFeatures(
    const features::TFeatureSet& all, const cv::Mat& depth, const cv::Mat& K, const cv::Mat& dist,
    const CRgbdOdometry::TOptions& o)
{
  TLiftedFeatures out;
  if (all.empty())
    return out;
  std::vector<cv::Point2f> pts;
  pts.reserve(all.size());
  for (const auto& k : all.keypoints)
    pts.push_back(k.pt);
  cv::undistortPoints(pts, out.rawUndistorted, K, dist, cv::noArray(), K);
  out.rawZ.assign(pts.size(), 0.0F);
  out.rowFraction.resize(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i)
  {
    // The depth image is registered to the (distorted) colour image, whose
    // rows are the ones read out in sequence.
    out.rowFraction[i] = static_cast<float>(pts[i].y / depth.rows - 0.5);
    const int u = static_cast<int>(std::lround(pts[i].x));
    const int v = static_cast<int>(std::lround(pts[i].y));
    if (u < 1 || v < 1 || u >= depth.cols - 1 || v >= depth.rows - 1)
      continue;
    const float z = depth.at<float>(v, u);
    if (!(z >= o.min_depth_m && z <= o.max_depth_m))
      continue;
    if (o.depth_discontinuity_m > 0)
    {
      float lo = z, hi = z;
      for (int dv = -1; dv <= 1; ++dv)
        for (int du = -1; du <= 1; ++du)
        {
          const float zz = depth.at<float>(v + dv, u + du);
          lo = std::min(lo, zz);
          hi = std::max(hi, zz);
        }
      if (lo <= 0 || hi - lo > o.depth_discontinuity_m * z)
        continue;
    }
    out.rawZ[i] = z;
    out.valid.push_back(static_cast<int>(i));
  }
  out.undistorted = out.rawUndistorted;
  out.z = out.rawZ;
  return out;
}

TKeyframe makeFeatureSet(
    const features::TFeatureSet& all, const TLiftedFeatures& lifted, const std::vector<int>& idx,
    const TPinhole& pinhole)
{
  TKeyframe k;
  k.features = all.select(idx);
  updateFeatureSetPoints(k, lifted, idx, pinhole);
  return k;
}

void updateFeatureSetPoints(
    TKeyframe& k, const TLiftedFeatures& lifted, const std::vector<int>& idx,
    const TPinhole& pinhole)
{
  k.points.clear();
  k.pixels.clear();
  k.points.reserve(idx.size());
  k.pixels.reserve(idx.size());
  for (int i : idx)
  {
    const auto& u = lifted.undistorted[static_cast<std::size_t>(i)];
    const double z = lifted.z[static_cast<std::size_t>(i)];
    k.points.emplace_back(
        (u.x - pinhole.cx) / pinhole.fx * z, (u.y - pinhole.cy) / pinhole.fy * z, z);
    k.pixels.push_back(u);
  }
}
void appendLifted(TLiftedFeatures& a, const TLiftedFeatures& b, int offset)
{
  for (int i : b.valid)
    a.valid.push_back(offset + i);
  auto append = [](auto& to, const auto& from) { to.insert(to.end(), from.begin(), from.end()); };
  append(a.undistorted, b.undistorted);
  append(a.z, b.z);
  append(a.rawUndistorted, b.rawUndistorted);
  append(a.rawZ, b.rawZ);
  append(a.rowFraction, b.rowFraction);
}
}  // namespace roislam::frontend::detail
