/* MRPT's name registry of deciders and optimisers for 3-D graphs, extended
 * with ours (CKeyframeNRD, CKeyframeERD, CKeyframeGSO), so they can be chosen
 * by name (e.g. CGraphSlamHandler::initEngine) and listed with descriptions
 * by `roi-graphslam --list-node-regs / --list-edge-regs`.
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

#include <string>

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

  /** "name: description" lines of the 3-D-capable registration deciders of
   *  type "node" or "edge" (MRPT's dumpRegistrarsToConsole prints to cout;
   *  this returns the text so the app prints it). */
  std::string describeRegistrars(const std::string& type) const;
};
}  // namespace roislam::graphslam
