/* graph.graph: a 3-D pose graph in MRPT's text format (VERTEX3, FIX and
 * EDGE3 lines, as CNetworkOfPoses::writeAsText writes them, which MRPT's
 * graph-slam tool opens), written and read back without loss.
 *
 * Two defects of Debian's MRPT 2.5.8 are worked around here:
 * - writeAsText prints with the stream's default 6 significant digits: a
 *   node 2 m out keeps 10 um, and an information entry loses what the next
 *   digits hold. We write the same text with every digit a double has.
 * - loadFromTextFile / readAsText lose three entries of every edge's
 *   information: the rotation block's off-diagonal ones (yaw-pitch,
 *   yaw-roll, pitch-roll). The reader stores them in the lower triangle,
 *   then copies the upper triangle, where they were never stored, over it.
 *   On our fr1/rpy graphs that left 152 of 395 edges with an information
 *   that is not positive definite (a negative chi-square). loadGraphText
 *   reads them where writeAsText took them from.
 * MRPT's tools still read our files with that loss; the README says so.
 */
#pragma once

#include <mrpt/graphs/CNetworkOfPoses.h>

#include <string>

namespace roislam::io
{
/** The graph as writeAsText writes it, every number with 17 significant
 *  digits (a double read back is the same double). */
std::string graphText(const mrpt::graphs::CNetworkOfPoses3DInf& graph);

/** graphText() into `file`, atomically; throws std::runtime_error naming the
 *  file when it cannot be written. */
void saveGraphText(const mrpt::graphs::CNetworkOfPoses3DInf& graph, const std::string& file);

/** A graph in that format: VERTEX3 id x y z roll pitch yaw, FIX id, EDGE3
 *  from to x y z roll pitch yaw and the 21 upper-triangle information
 *  entries in the file's (x y z roll pitch yaw) order; blank lines and lines
 *  starting with '#' are skipped. Throws std::runtime_error "<file>:<line>:
 *  <what>" on anything else: an unknown or malformed line, a duplicated node,
 *  an edge from a node to itself, an edge to a missing node, a FIX of a
 *  missing node; and "<file>: cannot
 *  open" or "<file>: no nodes". */
mrpt::graphs::CNetworkOfPoses3DInf loadGraphText(const std::string& file);
}  // namespace roislam::io
