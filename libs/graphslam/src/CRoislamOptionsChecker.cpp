#include <mrpt/system/string_utils.h>
#include <roislam/graphslam/CKeyframeERD.h>
#include <roislam/graphslam/CKeyframeGSO.h>
#include <roislam/graphslam/CKeyframeNRD.h>
#include <roislam/graphslam/CRoislamOptionsChecker.h>

#include <sstream>

namespace roislam::graphslam
{
CRoislamOptionsChecker::CRoislamOptionsChecker()
{
  createDeciderOptimizerMappings();
  populateDeciderOptimizerProperties();
}

CRoislamOptionsChecker::~CRoislamOptionsChecker() = default;

void CRoislamOptionsChecker::_createDeciderOptimizerMappings()
{
  node_regs_map[CKeyframeNRD::kName] = &createNodeRegistrationDecider<CKeyframeNRD>;
  edge_regs_map[CKeyframeERD::kName] = &createEdgeRegistrationDecider<CKeyframeERD>;
  optimizers_map[CKeyframeGSO::kName] = &createGraphSlamOptimizer<CKeyframeGSO>;
}

void CRoislamOptionsChecker::populateDeciderOptimizerProperties()
{
  TUserOptionsChecker<TGraph>::populateDeciderOptimizerProperties();
  auto addDecider = [&](const char* name, const char* description, const char* type)
  {
    auto* d = new mrpt::graphslam::apps::TRegistrationDeciderProps;
    d->name = name;
    d->description = description;
    d->type = type;
    d->rawlog_format = "Observation-only";
    d->observations_used.emplace_back("CObservation3DRangeScan (RGB + registered depth)");
    d->is_slam_2d = false;
    d->is_slam_3d = true;
    regs_descriptions.push_back(d);
  };
  addDecider(CKeyframeNRD::kName, CKeyframeNRD::kDescription, "Node");
  addDecider(CKeyframeERD::kName, CKeyframeERD::kDescription, "Edge");
  auto* o = new mrpt::graphslam::apps::TOptimizerProps;
  o->name = CKeyframeGSO::kName;
  o->description = CKeyframeGSO::kDescription;
  o->is_slam_2d = false;
  o->is_slam_3d = true;
  optimizers_descriptions.push_back(o);
}

std::string CRoislamOptionsChecker::describeRegistrars(const std::string& type) const
{
  std::ostringstream ss;
  for (const auto* d : regs_descriptions)
  {
    if (!mrpt::system::strCmpI(d->type, type) || !d->is_slam_3d)
      continue;
    // Only deciders that can actually be created for 3-D graphs.
    const bool available = mrpt::system::strCmpI(type, "node") ? node_regs_map.count(d->name) > 0
                                                               : edge_regs_map.count(d->name) > 0;
    if (!available)
      continue;
    ss << d->name << ": " << d->description << "\n";
  }
  return ss.str();
}
}  // namespace roislam::graphslam
