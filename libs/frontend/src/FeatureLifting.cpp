#include "FeatureLifting.h"

#include <roislam/geometry/KeypointLifting.h>

namespace roislam::frontend::detail
{
geometry::TDepthRule depthRule(const CRgbdOdometry::TOptions& o)
{
  geometry::TDepthRule rule;
  rule.min_depth_m = o.min_depth_m;
  rule.max_depth_m = o.max_depth_m;
  rule.depth_discontinuity_m = o.depth_discontinuity_m;
  return rule;
}

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
  geometry::TLiftedPixels lifted = geometry::liftPixels(pts, depth, K, dist, depthRule(o));
  out.valid = std::move(lifted.valid);
  out.rawUndistorted = std::move(lifted.undistorted);
  out.rawZ = std::move(lifted.z);
  out.readZ = out.rawZ;
  // The depth image is registered to the (distorted) colour image, whose rows
  // are the ones read out in sequence.
  out.rowFraction.resize(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i)
    out.rowFraction[i] = static_cast<float>(pts[i].y / depth.rows - 0.5);
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

void setKeyframeRate(TKeyframe& k, const TCameraRate& rate)
{
  k.angularRate = {rate.omega.x(), rate.omega.y(), rate.omega.z()};
  k.linearRate = {rate.linear.x(), rate.linear.y(), rate.linear.z()};
}

void updateFeatureSetPoints(
    TKeyframe& k, const TLiftedFeatures& lifted, const std::vector<int>& idx,
    const TPinhole& pinhole)
{
  k.points.clear();
  k.pixels.clear();
  setKeyframeRate(k, lifted.rate);
  k.points.reserve(idx.size());
  k.pixels.reserve(idx.size());
  for (int i : idx)
  {
    const auto& u = lifted.undistorted[static_cast<std::size_t>(i)];
    const Eigen::Vector3d X = pinhole.backProject(u, lifted.z[static_cast<std::size_t>(i)]);
    k.points.emplace_back(X.x(), X.y(), X.z());
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
  append(a.readZ, b.readZ);
  append(a.rowFraction, b.rowFraction);
}
}  // namespace roislam::frontend::detail
