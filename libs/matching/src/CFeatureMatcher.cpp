#include "roislam/matching/CFeatureMatcher.h"

#include <mrpt/config/CConfigFileBase.h>
#include <roislam/common/IniErrors.h>

#include <stdexcept>

#include "roislam/matching/CFeatureIndex.h"

namespace roislam::matching
{
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
  return CFeatureIndex(m_options, train).match(query);
}
}  // namespace roislam::matching
