/* What roi-eval needs of a run's frames.csv (CSlamOutputWriter): every
 * frame's time, and which frame each keyframe (graph node) is, so that a
 * saved graph.graph can be checked against ground truth after the run
 * (roi-eval --graph, the same statistics as summary.json's edge_chi2).
 */
#pragma once

#include <mrpt/graphs/TNodeID.h>

#include <map>
#include <string>
#include <vector>

namespace roislam::evaluation
{
struct TFrameTimes
{
  /** Graph node -> its frame's time (the frames.csv "keyframe" column names
   *  the node a frame became). */
  std::map<mrpt::graphs::TNodeID, double> keyframes;
  /** Every frame's time, sorted. */
  std::vector<double> frames;
};

/** Reads the "timestamp" and "keyframe" columns (found by the header, so
 *  other columns may come and go). Throws std::runtime_error "<file>:<line>:
 *  <what>" on a missing column, a row with too few fields, a time or node
 *  that is not a number, or a node named twice; "<file>: cannot open" and
 *  "<file>: no frames". */
TFrameTimes readFrameTimes(const std::string& framesCsv);
}  // namespace roislam::evaluation
