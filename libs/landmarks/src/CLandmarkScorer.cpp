#include "roislam/landmarks/CLandmarkScorer.h"

#include <roislam/common/IniErrors.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>

#include "IniRead.h"

namespace roislam::landmarks
{
void CLandmarkScorer::TOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& s)
{
  match_radius = detail::readDouble(c, s, "match_radius", match_radius);
  max_time_difference = detail::readDouble(c, s, "max_time_difference", max_time_difference);
  interpolate = detail::readBool(c, s, "interpolate", interpolate);
  recall_position = c.read_string(s, "recall_position", recall_position);
  if (recall_position != "landmark_point" && recall_position != "roi_median")
    common::throwBadIniKey(
        s, "recall_position",
        "unknown value '" + recall_position + "' (expected landmark_point or roi_median)");
  detail::require(match_radius > 0, s, "match_radius", match_radius, "> 0");
  detail::require(max_time_difference > 0, s, "max_time_difference", max_time_difference, "> 0");
}

void CLandmarkScorer::TOptions::saveToConfigFile(
    mrpt::config::CConfigFileBase& c, const std::string& s) const
{
  c.write(s, "match_radius", match_radius);
  c.write(s, "max_time_difference", max_time_difference);
  c.write(s, "interpolate", interpolate);
  c.write(s, "recall_position", recall_position);
}

const char* toString(CLandmarkScorer::EOutcome outcome)
{
  switch (outcome)
  {
    case CLandmarkScorer::EOutcome::TruePositive:
      return "TP";
    case CLandmarkScorer::EOutcome::FalsePositive:
      return "FP";
    case CLandmarkScorer::EOutcome::FalseNegative:
      return "FN";
    case CLandmarkScorer::EOutcome::TrueNegative:
      return "TN";
    case CLandmarkScorer::EOutcome::Unscored:
      return "";
  }
  return "";
}

CLandmarkScorer::CLandmarkScorer(const TOptions& options, io::TTrajectory groundTruth)
    : m_options(options), m_gt(std::move(groundTruth))
{
  std::sort(
      m_gt.begin(), m_gt.end(),
      [](const auto& a, const auto& b) { return a.timestamp < b.timestamp; });
}

std::optional<mrpt::poses::CPose3D> CLandmarkScorer::poseAt(double t) const
{
  return io::poseAt(m_gt, t, m_options.max_time_difference, m_options.interpolate);
}

CLandmarkScorer::TScore CLandmarkScorer::score(const std::vector<TEvent>& events) const
{
  TScore out;
  // World position of each landmark at its first sight (nullopt: unscorable).
  std::map<int32_t, std::optional<mrpt::math::TPoint3D>> landmarkWorld;

  for (const auto& e : events)
  {
    std::optional<mrpt::math::TPoint3D> world;
    if (e.roiPosition)
      if (const auto pose = poseAt(e.timestamp))
        world = pose->composePoint(*e.roiPosition);

    EOutcome outcome = EOutcome::Unscored;
    if (e.isNew)
    {
      if (world)
      {
        const bool duplicate = std::any_of(
            landmarkWorld.begin(), landmarkWorld.end(),
            [&](const auto& kv)
            { return kv.second && (*kv.second - *world).norm() <= m_options.match_radius; });
        outcome = duplicate ? EOutcome::FalseNegative : EOutcome::TrueNegative;
      }
      landmarkWorld[e.landmarkId] = world;
    }
    else
    {
      const auto it = landmarkWorld.find(e.landmarkId);
      if (world && it != landmarkWorld.end() && it->second)
        outcome = (*it->second - *world).norm() <= m_options.match_radius ? EOutcome::TruePositive
                                                                          : EOutcome::FalsePositive;
    }

    switch (outcome)
    {
      case EOutcome::TruePositive:
        ++out.truePositives;
        break;
      case EOutcome::FalsePositive:
        ++out.falsePositives;
        break;
      case EOutcome::FalseNegative:
        ++out.falseNegatives;
        break;
      case EOutcome::TrueNegative:
        ++out.trueNegatives;
        break;
      case EOutcome::Unscored:
        ++out.unscored;
        break;
    }
    out.outcomes.push_back(outcome);
  }
  if (out.truePositives + out.falsePositives > 0)
    out.precision = double(out.truePositives) / (out.truePositives + out.falsePositives);
  if (out.truePositives + out.falseNegatives > 0)
    out.recall = double(out.truePositives) / (out.truePositives + out.falseNegatives);
  return out;
}
}  // namespace roislam::landmarks
