#include <mrpt/system/string_utils.h>
#include <roislam/graphslam/CKeyframeERD.h>
#include <roislam/graphslam/CKeyframeGSO.h>
#include <roislam/graphslam/CKeyframeNRD.h>
#include <roislam/graphslam/CRoislamOptionsChecker.h>

#include <map>
#include <sstream>
#include <stdexcept>

namespace roislam::graphslam
{
namespace
{
/** Why MRPT's own 3-D-capable classes cannot run here (the 2-D ones are
 *  refused by their properties). */
const std::map<std::string, std::string>& knownRefusals()
{
  static const std::map<std::string, std::string> r{
      {"CFixedIntervalsNRD",
       "registers nodes from odometry (CObservationOdometry or actions), which RGB-D rawlogs do "
       "not carry; the outputs and our edge decider and optimiser need CKeyframeNRD's front end"},
      {"CEmptyNRD",
       "registers no nodes; the outputs and our edge decider and optimiser need CKeyframeNRD's "
       "front end"},
      {"CEmptyGSO",
       "abstract in MRPT 2.5 (no optimizeGraph()): its name silently builds a CLevMarqGSO; "
       "choose CLevMarqGSO"}};
  return r;
}

std::string typeLabel(const std::string& type)
{
  if (mrpt::system::strCmpI(type, "node"))
    return "node registration decider";
  if (mrpt::system::strCmpI(type, "edge"))
    return "edge registration decider";
  return "optimizer";
}
}  // namespace

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

std::string CRoislamOptionsChecker::refusal(const std::string& type, const std::string& name) const
{
  const bool optimizer = mrpt::system::strCmpI(type, "optimizer");
  bool known = false, is3d = false;
  if (optimizer)
  {
    for (const auto* o : optimizers_descriptions)
      if (o->name == name)
        known = true, is3d = o->is_slam_3d;
  }
  else
  {
    for (const auto* d : regs_descriptions)
      if (d->name == name && mrpt::system::strCmpI(d->type, type))
        known = true, is3d = d->is_slam_3d;
  }
  if (!known)
    return "unknown (--list-" + std::string(optimizer ? "optimizers" : type + "-regs") +
           " lists them)";
  if (!is3d)
    return "works on 2-D graphs only (MRPT 2.5 registers it for 2-D SLAM); roislam builds 3-D "
           "graphs";
  const auto it = knownRefusals().find(name);
  if (it != knownRefusals().end())
    return it->second;
  // What TUserOptionsChecker describes but cannot build for 3-D graphs.
  const bool built = optimizer
                         ? optimizers_map.count(name) > 0
                         : (mrpt::system::strCmpI(type, "node") ? node_regs_map.count(name)
                                                                : edge_regs_map.count(name)) > 0;
  return built ? std::string() : "not built for 3-D graphs by MRPT 2.5's TUserOptionsChecker";
}

TSlamDeciders CRoislamOptionsChecker::createDeciders(
    const TSlamDeciders::TNames& names, const CSlamContext::TConfig* config) const
{
  for (const auto& [type, name] :
       {std::pair<std::string, std::string>{"node", names.node},
        {"edge", names.edge},
        {"optimizer", names.optimizer}})
  {
    const std::string why = refusal(type, name);
    if (!why.empty())
      throw std::invalid_argument(typeLabel(type) + " '" + name + "': " + why);
  }
  TSlamDeciders d;
  d.names = names;
  d.node.reset(node_regs_map.at(names.node)());
  d.edge.reset(edge_regs_map.at(names.edge)());
  d.optimizer.reset(optimizers_map.at(names.optimizer)());
  d.context = config
                  ? std::make_shared<CSlamContext>(*config)
                  : std::make_shared<CSlamContext>(
                        CSlamContext::TConfig(), CSlamContext::EConfigOrigin::DecidersLoadParams);
  if (auto* n = d.ourNode())
    n->setContext(d.context);
  if (auto* e = d.ourEdge())
    e->setContext(d.context);
  if (auto* o = d.ourOptimizer())
    o->setContext(d.context);
  return d;
}

std::string CRoislamOptionsChecker::listing(
    const std::string& type, const std::vector<std::pair<std::string, std::string>>& entries) const
{
  std::ostringstream usable, refused;
  for (const auto& [name, description] : entries)
  {
    const std::string why = refusal(type, name);
    (why.empty() ? usable : refused) << name << ": " << (why.empty() ? description : why) << "\n";
  }
  const std::string no = refused.str();
  return usable.str() + (no.empty() ? std::string() : "not usable here:\n" + no);
}

std::string CRoislamOptionsChecker::describeRegistrars(const std::string& type) const
{
  std::vector<std::pair<std::string, std::string>> entries;
  for (const auto* d : regs_descriptions)
    if (mrpt::system::strCmpI(d->type, type))
      entries.emplace_back(d->name, d->description);
  return listing(type, entries);
}

std::string CRoislamOptionsChecker::describeOptimizers() const
{
  std::vector<std::pair<std::string, std::string>> entries;
  for (const auto* o : optimizers_descriptions)
    entries.emplace_back(o->name, o->description);
  return listing("optimizer", entries);
}
}  // namespace roislam::graphslam
