/* MRPT's name registry of deciders and optimisers for 3-D graphs, extended
 * with ours (CKeyframeNRD, CKeyframeERD, CKeyframeGSO), and the factory that
 * builds the three of a run by name (createDeciders()), which is also where
 * the context our deciders share is created: MRPT's by-name factories are
 * plain functions without arguments, so they cannot hand one context to
 * several deciders. Lists them for `--list-node-regs` etc. of
 * roi-graphslam-engine (and roi-graphslam), with the reason why those that
 * cannot run here are refused:
 *  - CKeyframeNRD is the only node decider: the outputs (every frame's pose,
 *    frames.csv, map.bt) and our edge decider and optimiser need its front
 *    end; MRPT's CFixedIntervalsNRD registers nodes from odometry, which
 *    RGB-D rawlogs do not carry, CEmptyNRD none, CICPCriteriaNRD is 2-D only;
 *  - edge deciders: CKeyframeERD, or MRPT's CEmptyERD (an odometry-only
 *    graph); CICPCriteriaERD and CLoopCloserERD are 2-D only;
 *  - optimisers: CKeyframeGSO, or MRPT's CLevMarqGSO; CEmptyGSO is abstract
 *    in MRPT 2.5 (its name silently builds a CLevMarqGSO).
 */
#pragma once

// CLevMarqGSO_impl.h (pulled in below) and the ERDs use CDisk, CSphere and CConfigFile without
// including them (MRPT 2.5.8).
#include <mrpt/config/CConfigFile.h>
#include <mrpt/opengl/CDisk.h>
#include <mrpt/opengl/CSphere.h>
// The decider headers rely on the global `using namespace std` that
// CNodeRegistrationDecider_impl.h introduces, so it must come first.
#include <mrpt/graphslam/interfaces/CNodeRegistrationDecider.h>
//
#include <mrpt/graphslam/apps_related/TUserOptionsChecker.h>
#include <roislam/graphslam/CSlamContext.h>
#include <roislam/graphslam/TSlamDeciders.h>

#include <string>
#include <utility>
#include <vector>

namespace roislam::graphslam
{
class CRoislamOptionsChecker : public mrpt::graphslam::apps::TUserOptionsChecker<TGraph>
{
 public:
  /** Fills the maps and descriptions (MRPT's own, then ours). */
  CRoislamOptionsChecker();
  ~CRoislamOptionsChecker() override;

  void _createDeciderOptimizerMappings() override;
  void populateDeciderOptimizerProperties() override;

  /** Empty when the class `name` of `type` ("node", "edge" or "optimizer")
   *  can run here, else why not (unknown, 2-D only, or see above). */
  std::string refusal(const std::string& type, const std::string& name) const;

  /** The deciders and optimiser named `names`, and, for ours, one context
   *  they share: configured by `config` when given (their loadParams() then
   *  read nothing), else by their loadParams() from the engine's ini. Throws
   *  std::invalid_argument "<type> '<name>': <refusal>" for a name that
   *  cannot run here. */
  TSlamDeciders createDeciders(
      const TSlamDeciders::TNames& names, const CSlamContext::TConfig* config = nullptr) const;

  /** "name: description" lines of the node ("node") or edge ("edge")
   *  registration deciders that can run here, then those that cannot, with
   *  the reason (MRPT's dumpRegistrarsToConsole prints to cout and lists
   *  2-D ones as if they could). */
  std::string describeRegistrars(const std::string& type) const;
  /** The same for the optimisers. */
  std::string describeOptimizers() const;

 private:
  /** Usable entries (name: description), then "not usable here:" ones. */
  std::string listing(
      const std::string& type,
      const std::vector<std::pair<std::string, std::string>>& entries) const;
};
}  // namespace roislam::graphslam
