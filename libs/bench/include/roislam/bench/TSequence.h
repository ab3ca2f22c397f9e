/* One input sequence of the benchmark (a TUM-layout folder). Found by
 * CExperimentPlan::discoverSequences(), read by the plan and the report.
 */
#pragma once

#include <string>

namespace roislam::bench
{
struct TSequence
{
  std::string name;             //!< folder name, made unique within a plan (used in run ids)
  std::string path;             //!< absolute folder path
  bool hasGroundTruth = false;  //!< groundtruth.txt present (7-Scenes: its pose files)
};
}  // namespace roislam::bench
