#include "roislam/features/CFeatureExtractor.h"

#include <mrpt/config/CConfigFileBase.h>
#include <roislam/common/IniErrors.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "roislam/features/CSurf.h"

namespace roislam::features
{
void CFeatureExtractor::TOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& s)
{
  const std::string type = c.read_string(s, "feature_type", toString(feature_type));
  try
  {
    feature_type = featureTypeFromString(type);
  }
  catch (const std::invalid_argument& e)
  {
    common::throwBadIniKey(s, "feature_type", e.what());
  }
  max_features = c.read_int(s, "max_features", max_features);
  surf_hessian_threshold = c.read_double(s, "surf_hessian_threshold", surf_hessian_threshold);
  surf_octaves = c.read_int(s, "surf_octaves", surf_octaves);
  surf_octave_layers = c.read_int(s, "surf_octave_layers", surf_octave_layers);
  surf_extended = c.read_bool(s, "surf_extended", surf_extended);
  surf_upright = c.read_bool(s, "surf_upright", surf_upright);
  if (max_features < 0)
    common::throwBadIniKey(s, "max_features", "must be >= 0 (0 = no cap)");
  if (!(surf_hessian_threshold > 0))
    common::throwBadIniKey(s, "surf_hessian_threshold", "must be > 0");
  if (surf_octaves < 1)
    common::throwBadIniKey(s, "surf_octaves", "must be >= 1");
  if (surf_octave_layers < 1)
    common::throwBadIniKey(s, "surf_octave_layers", "must be >= 1");
}

void CFeatureExtractor::TOptions::saveToConfigFile(
    mrpt::config::CConfigFileBase& c, const std::string& s) const
{
  c.write(s, "feature_type", toString(feature_type));
  c.write(s, "max_features", max_features);
  c.write(s, "surf_hessian_threshold", surf_hessian_threshold);
  c.write(s, "surf_octaves", surf_octaves);
  c.write(s, "surf_octave_layers", surf_octave_layers);
  c.write(s, "surf_extended", surf_extended);
  c.write(s, "surf_upright", surf_upright);
}

CFeatureExtractor::CFeatureExtractor() : CFeatureExtractor(TOptions()) {}

CFeatureExtractor::CFeatureExtractor(const TOptions& options) : m_options(options)
{
  if (m_options.max_features < 0)
    throw std::invalid_argument("CFeatureExtractor: max_features must be >= 0");
  // SIFT and SURF: cap 0 keeps all, otherwise the best N by response. ORB
  // needs a budget: without a cap, extractAll() allows 10 x max_features
  // (at least 5000).
  m_detector = detectorWithCap(m_options.max_features);
  if (m_options.feature_type == EFeatureType::ORB)
    m_uncapped = detectorWithCap(std::max(5000, 10 * m_options.max_features));
  else
    m_uncapped = m_options.max_features > 0 ? detectorWithCap(0) : m_detector;
}

namespace
{
cv::Mat toGrey(const cv::Mat& image)
{
  cv::Mat grey = image;
  if (image.channels() == 3)
    cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  else if (image.channels() == 4)
    cv::cvtColor(image, grey, cv::COLOR_BGRA2GRAY);
  if (grey.type() != CV_8UC1)
    throw std::invalid_argument("CFeatureExtractor::extract: expected an 8-bit grey or BGR image");
  return grey;
}

TFeatureSet detectSorted(
    cv::Feature2D& detector, EFeatureType type, const cv::Mat& grey, const cv::Mat& mask, int cap)
{
  TFeatureSet out;
  out.type = type;
  cv::Mat desc;
  detector.detectAndCompute(grey, mask, out.keypoints, desc);

  // Strongest first, capped: detectors differ in whether (and how exactly) they
  // honour a cap, so the order and the cap are enforced here uniformly.
  std::vector<int> order(out.keypoints.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(
      order.begin(), order.end(),
      [&](int a, int b) { return out.keypoints[a].response > out.keypoints[b].response; });
  if (cap > 0 && order.size() > static_cast<std::size_t>(cap))
    order.resize(static_cast<std::size_t>(cap));
  out.descriptors = desc;
  return out.select(order);
}
}  // namespace

TFeatureSet CFeatureExtractor::extract(const cv::Mat& image, const cv::Mat& mask) const
{
  return detectSorted(
      *m_detector, m_options.feature_type, toGrey(image), mask, m_options.max_features);
}

TFeatureSet CFeatureExtractor::extractAll(const cv::Mat& image) const
{
  return detectSorted(*m_uncapped, m_options.feature_type, toGrey(image), cv::Mat(), 0);
}

cv::Ptr<cv::Feature2D> CFeatureExtractor::detectorWithCap(int cap) const
{
  switch (m_options.feature_type)
  {
    case EFeatureType::SIFT:
      return cv::SIFT::create(cap);
    case EFeatureType::ORB:
      // ORB's budget is also its cost (Harris scores and descriptors).
      return cv::ORB::create(cap > 0 ? cap : 500);
    case EFeatureType::SURF:
    {
      CSurf::TParams p;
      p.hessianThreshold = m_options.surf_hessian_threshold;
      p.nOctaves = m_options.surf_octaves;
      p.nOctaveLayers = m_options.surf_octave_layers;
      p.extended = m_options.surf_extended;
      p.upright = m_options.surf_upright;
      p.maxFeatures = cap;
      return CSurf::create(p);
    }
  }
  throw std::logic_error("CFeatureExtractor: unknown feature type");
}

int CFeatureExtractor::supportPx() const
{
  // A keypoint is found and described from the pixels within about this
  // distance at the finest scales; coarser ones near the rim are lost, as
  // they would be at the image's border.
  switch (m_options.feature_type)
  {
    case EFeatureType::ORB:
      return 31;  // OpenCV's edgeThreshold = patchSize = 31
    case EFeatureType::SIFT:
      return 16;  // SIFT_IMG_BORDER 5 px per octave + the 4x4 window's half
    case EFeatureType::SURF:
      return 26;  // half the 51-px filter of the second octave
  }
  return 32;
}

TFeatureSet CFeatureExtractor::extractIn(
    const cv::Mat& image, const cv::Rect& region, int cap, std::size_t* describedPixels) const
{
  const cv::Mat grey = toGrey(image);
  const cv::Rect bounds(0, 0, grey.cols, grey.rows);
  const cv::Rect inner = region & bounds;
  const int m = supportPx();
  const cv::Rect padded =
      cv::Rect(inner.x - m, inner.y - m, inner.width + 2 * m, inner.height + 2 * m) & bounds;
  if (describedPixels)
    *describedPixels = inner.empty() ? 0 : static_cast<std::size_t>(padded.area());
  TFeatureSet out;
  out.type = m_options.feature_type;
  if (inner.empty())
    return out;
  // The detector's own budget (which is also ORB's and SIFT's cost: scores
  // and descriptors) covers the padding's share of the crop too.
  const int detCap =
      cap > 0 ? static_cast<int>(std::ceil(cap * static_cast<double>(padded.area()) / inner.area()))
              : 0;
  const auto detector = detectorWithCap(detCap);
  TFeatureSet crop = detectSorted(*detector, m_options.feature_type, grey(padded), cv::Mat(), 0);
  // Back to image coordinates; only the region's own keypoints, strongest
  // first, then the cap (applied after the region filter, so the padding's
  // keypoints never take the region's budget).
  const cv::Rect2f box(inner);
  std::vector<int> keep;
  for (std::size_t i = 0; i < crop.size(); ++i)
  {
    auto& k = crop.keypoints[i];
    k.pt.x += static_cast<float>(padded.x);
    k.pt.y += static_cast<float>(padded.y);
    if (box.contains(k.pt) && (cap <= 0 || keep.size() < static_cast<std::size_t>(cap)))
      keep.push_back(static_cast<int>(i));
  }
  return crop.select(keep);
}

TFeatureSet CFeatureExtractor::capWithRegion(
    const TFeatureSet& strongestFirst, const cv::Rect& region) const
{
  const std::size_t n = static_cast<std::size_t>(m_options.max_features);
  if (n == 0)
    return strongestFirst;
  const cv::Rect2f box(region);
  std::vector<int> keep;
  std::size_t inRegion = 0;
  for (std::size_t i = 0; i < strongestFirst.size(); ++i)
  {
    const bool inside = box.contains(strongestFirst.keypoints[i].pt);
    // The order is strongest first: the first n overall, and the first n
    // inside the region, whichever list a feature belongs to.
    if (i < n || (inside && inRegion < n))
      keep.push_back(static_cast<int>(i));
    if (inside)
      ++inRegion;
    if (i + 1 >= n && inRegion >= n)
      break;
  }
  return strongestFirst.select(keep);
}

}  // namespace roislam::features