#include "roislam/matching/CFeatureMatcher.h"

#include <mrpt/config/CConfigFileBase.h>
#include <roislam/common/IniErrors.h>

#include <opencv2/features2d.hpp>
#include <opencv2/flann.hpp>
#include <stdexcept>

namespace roislam::matching
{
namespace
{
cv::Ptr<cv::DescriptorMatcher> makeMatcher(EMatcherType type, bool binary)
{
  if (type == EMatcherType::BRUTE_FORCE)
    return cv::BFMatcher::create(binary ? cv::NORM_HAMMING : cv::NORM_L2);
  if (binary)
    // Multi-probe LSH as recommended by FLANN for binary descriptors.
    return cv::makePtr<cv::FlannBasedMatcher>(
        cv::makePtr<cv::flann::LshIndexParams>(6, 12, 1), cv::makePtr<cv::flann::SearchParams>(32));
  return cv::makePtr<cv::FlannBasedMatcher>(
      cv::makePtr<cv::flann::KDTreeIndexParams>(4), cv::makePtr<cv::flann::SearchParams>(32));
}

// One direction: best match per query row that passes the ratio test.
std::vector<cv::DMatch> ratioMatches(
    const cv::Mat& query, const cv::Mat& train, EMatcherType type, bool binary, double ratio)
{
  std::vector<std::vector<cv::DMatch>> knn;
  makeMatcher(type, binary)->knnMatch(query, train, knn, 2);
  std::vector<cv::DMatch> out;
  out.reserve(knn.size());
  for (const auto& k : knn)
  {
    if (k.empty())
      continue;
    // A single candidate (tiny train set, or LSH finding one bucket) has no
    // second neighbour to compare with; it is kept only with ratio 1.
    if (k.size() == 1)
    {
      if (ratio >= 1.0)
        out.push_back(k[0]);
      continue;
    }
    if (k[0].distance <= ratio * k[1].distance)
      out.push_back(k[0]);
  }
  return out;
}
}  // namespace

void CFeatureMatcher::TOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& s)
{
  const std::string m =
      c.read_string(s, "matcher", matcher == EMatcherType::FLANN ? "flann" : "brute_force");
  if (m == "flann")
    matcher = EMatcherType::FLANN;
  else if (m == "brute_force")
    matcher = EMatcherType::BRUTE_FORCE;
  else
    common::throwBadIniKey(
        s, "matcher", "unknown matcher '" + m + "' (expected flann or brute_force)");
  ratio = c.read_double(s, "ratio", ratio);
  cross_check = c.read_bool(s, "cross_check", cross_check);
  if (!(ratio > 0 && ratio <= 1))
    common::throwBadIniKey(s, "ratio", "must be in (0, 1]");
}

void CFeatureMatcher::TOptions::saveToConfigFile(
    mrpt::config::CConfigFileBase& c, const std::string& s) const
{
  c.write(s, "matcher", matcher == EMatcherType::FLANN ? "flann" : "brute_force");
  c.write(s, "ratio", ratio);
  c.write(s, "cross_check", cross_check);
}

CFeatureMatcher::CFeatureMatcher() : CFeatureMatcher(TOptions()) {}

CFeatureMatcher::CFeatureMatcher(const TOptions& options) : m_options(options)
{
  if (!(m_options.ratio > 0 && m_options.ratio <= 1))
    throw std::invalid_argument("CFeatureMatcher: ratio must be in (0, 1]");
}

std::vector<cv::DMatch> CFeatureMatcher::match(
    const features::TFeatureSet& query, const features::TFeatureSet& train) const
{
  if (query.empty() || train.empty())
    return {};
  if (query.type != train.type || query.descriptors.type() != train.descriptors.type() ||
      query.descriptors.cols != train.descriptors.cols)
    throw std::invalid_argument("CFeatureMatcher::match: feature sets of different types");
  const bool binary = features::isBinary(query.type);
  auto fwd = ratioMatches(
      query.descriptors, train.descriptors, m_options.matcher, binary, m_options.ratio);
  if (!m_options.cross_check)
    return fwd;

  // Mutual check: the train feature's own best match must be the query feature.
  std::vector<std::vector<cv::DMatch>> back;
  makeMatcher(m_options.matcher, binary)->knnMatch(train.descriptors, query.descriptors, back, 1);
  std::vector<cv::DMatch> out;
  for (const auto& m : fwd)
  {
    const auto& b = back[static_cast<std::size_t>(m.trainIdx)];
    if (!b.empty() && b[0].trainIdx == m.queryIdx)
      out.push_back(m);
  }
  return out;
}
}  // namespace roislam::matching
