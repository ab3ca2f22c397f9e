#include "roislam/features/TFeatureSet.h"

#include <mrpt/system/string_utils.h>

#include <stdexcept>

namespace roislam::features
{
EFeatureType featureTypeFromString(const std::string& s)
{
  const std::string l = mrpt::system::lowerCase(s);
  if (l == "sift")
    return EFeatureType::SIFT;
  if (l == "surf")
    return EFeatureType::SURF;
  if (l == "orb")
    return EFeatureType::ORB;
  throw std::invalid_argument("unknown feature type '" + s + "' (expected sift, surf or orb)");
}

double finestScaleSigmaPx(EFeatureType t)
{
  // The sigma at which each detector's feature edges read a chi-square
  // against ground truth as expected on four rendered 300-frame loops
  // (ICL-like, Kinect-v2-like, fr1-like, unregistered; rendered images have
  // no camera share). feature-bench's loc_px, the detector alone between an
  // image and its warp (same pixels' noise), reads lower, in the same order
  // (rot5: ORB 0.37-0.41, SURF 0.07-0.12, SIFT 0.05-0.07): a registration
  // adds independent image noise and perspective between its two frames.
  switch (t)
  {
    case EFeatureType::SIFT:
      return 0.31;
    case EFeatureType::SURF:
      return 0.46;
    case EFeatureType::ORB:
      return 0.72;
  }
  return 1.0;
}

std::string toString(EFeatureType t)
{
  switch (t)
  {
    case EFeatureType::SIFT:
      return "sift";
    case EFeatureType::SURF:
      return "surf";
    case EFeatureType::ORB:
      return "orb";
  }
  return "unknown";
}

TFeatureSet TFeatureSet::select(const std::vector<int>& indices) const
{
  TFeatureSet out;
  out.type = type;
  out.keypoints.reserve(indices.size());
  if (!indices.empty())
    out.descriptors.create(static_cast<int>(indices.size()), descriptors.cols, descriptors.type());
  for (std::size_t k = 0; k < indices.size(); ++k)
  {
    out.keypoints.push_back(keypoints.at(static_cast<std::size_t>(indices[k])));
    descriptors.row(indices[k]).copyTo(out.descriptors.row(static_cast<int>(k)));
  }
  return out;
}

TFeatureSet concat(const TFeatureSet& a, const TFeatureSet& b)
{
  if (b.empty())
    return a;
  if (a.empty())
    return b;
  if (a.type != b.type)
    throw std::invalid_argument("concat: feature sets of different types");
  TFeatureSet out;
  out.type = a.type;
  out.keypoints = a.keypoints;
  out.keypoints.insert(out.keypoints.end(), b.keypoints.begin(), b.keypoints.end());
  cv::vconcat(a.descriptors, b.descriptors, out.descriptors);
  return out;
}

TFeatureSet TFeatureSet::subset(const cv::Rect& rect) const
{
  std::vector<int> inside;
  const cv::Rect2f r(rect);
  for (std::size_t i = 0; i < keypoints.size(); ++i)
    if (r.contains(keypoints[i].pt))
      inside.push_back(static_cast<int>(i));
  return select(inside);
}
}  // namespace roislam::features
