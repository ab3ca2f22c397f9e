#include "roislam/features/CFeatureExtractor.h"

#include <mrpt/config/CConfigFileBase.h>
#include <roislam/common/IniErrors.h>

#include <algorithm>
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
  switch (m_options.feature_type)
  {
    case EFeatureType::SIFT:
      // nfeatures = 0 keeps all, otherwise OpenCV keeps the best N by response.
      m_detector = cv::SIFT::create(m_options.max_features);
      break;
    case EFeatureType::ORB:
      m_detector = cv::ORB::create(m_options.max_features > 0 ? m_options.max_features : 500);
      break;
    case EFeatureType::SURF:
    {
      CSurf::TParams p;
      p.hessianThreshold = m_options.surf_hessian_threshold;
      p.nOctaves = m_options.surf_octaves;
      p.nOctaveLayers = m_options.surf_octave_layers;
      p.extended = m_options.surf_extended;
      p.upright = m_options.surf_upright;
      p.maxFeatures = m_options.max_features;
      m_detector = CSurf::create(p);
      break;
    }
  }
}

TFeatureSet CFeatureExtractor::extract(const cv::Mat& image, const cv::Mat& mask) const
{
  cv::Mat grey = image;
  if (image.channels() == 3)
    cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  else if (image.channels() == 4)
    cv::cvtColor(image, grey, cv::COLOR_BGRA2GRAY);
  if (grey.type() != CV_8UC1)
    throw std::invalid_argument("CFeatureExtractor::extract: expected an 8-bit grey or BGR image");

  TFeatureSet out;
  out.type = m_options.feature_type;
  cv::Mat desc;
  m_detector->detectAndCompute(grey, mask, out.keypoints, desc);

  // Strongest first, capped: detectors differ in whether (and how exactly) they
  // honour a cap, so the order and the cap are enforced here uniformly.
  std::vector<int> order(out.keypoints.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(
      order.begin(), order.end(),
      [&](int a, int b) { return out.keypoints[a].response > out.keypoints[b].response; });
  if (m_options.max_features > 0 && order.size() > static_cast<std::size_t>(m_options.max_features))
    order.resize(static_cast<std::size_t>(m_options.max_features));
  out.descriptors = desc;
  return out.select(order);
}
}  // namespace roislam::features
