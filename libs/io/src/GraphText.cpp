#include "roislam/io/GraphText.h"

#include <roislam/common/TextFiles.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace roislam::io
{
namespace
{
// The file's angle order is roll, pitch, yaw; MRPT's pose and information
// order is yaw, pitch, roll. Entry k of the file's 6-vector is entry
// kToMrpt[k] of MRPT's.
constexpr int kToMrpt[6] = {0, 1, 2, 5, 4, 3};

/** Reads `n` finite numbers; false when the line has fewer, or one is not a
 *  number or not finite. */
bool readNumbers(std::istringstream& in, double* out, int n)
{
  for (int i = 0; i < n; ++i)
    if (!(in >> out[i]) || !std::isfinite(out[i]))
      return false;
  return true;
}

bool atEnd(std::istringstream& in)
{
  std::string rest;
  return !(in >> rest);
}

mrpt::poses::CPose3D poseFromFile(const double* v)
{
  // v: x y z roll pitch yaw.
  return mrpt::poses::CPose3D(v[0], v[1], v[2], v[5], v[4], v[3]);
}
}  // namespace

std::string graphText(const mrpt::graphs::CNetworkOfPoses3DInf& graph)
{
  std::ostringstream out;
  out.precision(std::numeric_limits<double>::max_digits10);
  graph.writeAsText(out);
  return out.str();
}

void saveGraphText(const mrpt::graphs::CNetworkOfPoses3DInf& graph, const std::string& file)
{
  common::writeFileAtomically(file, graphText(graph));
}

mrpt::graphs::CNetworkOfPoses3DInf loadGraphText(const std::string& file)
{
  std::istringstream text(common::readFile(file));
  mrpt::graphs::CNetworkOfPoses3DInf g;
  std::vector<mrpt::graphs::TNodeID> fixed;
  std::size_t lineNo = 0;
  const auto fail = [&](const std::string& what)
  { return std::runtime_error(file + ":" + std::to_string(lineNo) + ": " + what); };
  for (std::string line; std::getline(text, line);)
  {
    ++lineNo;
    std::istringstream in(line);
    std::string key;
    if (!(in >> key) || key[0] == '#')
      continue;
    if (key == "VERTEX3")
    {
      mrpt::graphs::TNodeID id;
      double v[6];
      if (!(in >> id) || !readNumbers(in, v, 6) || !atEnd(in))
        throw fail("malformed VERTEX3 line (VERTEX3 id x y z roll pitch yaw)");
      if (!g.nodes.emplace(id, poseFromFile(v)).second)
        throw fail("node " + std::to_string(id) + " listed twice");
    }
    else if (key == "FIX")
    {
      mrpt::graphs::TNodeID id;
      if (!(in >> id) || !atEnd(in))
        throw fail("malformed FIX line (FIX id)");
      fixed.push_back(id);
      g.root = id;
    }
    else if (key == "EDGE3")
    {
      mrpt::graphs::TNodeID from, to;
      double v[6], inf[21];
      if (!(in >> from >> to) || !readNumbers(in, v, 6) || !readNumbers(in, inf, 21) || !atEnd(in))
        throw fail(
            "malformed EDGE3 line (EDGE3 from to x y z roll pitch yaw and 21 information "
            "entries)");
      // MRPT's writer skips such an edge: it would not come back.
      if (from == to)
        throw fail("EDGE3 from node " + std::to_string(from) + " to itself");
      mrpt::poses::CPose3DPDFGaussianInf edge;
      edge.mean = poseFromFile(v);
      // The upper triangle row by row in the file's order, each entry put
      // where MRPT's writer took it from, and mirrored.
      int k = 0;
      for (int r = 0; r < 6; ++r)
        for (int c = r; c < 6; ++c, ++k)
        {
          edge.cov_inv(kToMrpt[r], kToMrpt[c]) = inf[k];
          edge.cov_inv(kToMrpt[c], kToMrpt[r]) = inf[k];
        }
      g.insertEdge(from, to, edge);
    }
    else
      throw fail("unknown line '" + key + "' (expected VERTEX3, FIX or EDGE3)");
  }
  if (g.nodes.empty())
    throw std::runtime_error(file + ": no nodes (no VERTEX3 line)");
  for (const auto id : fixed)
    if (!g.nodes.count(id))
      throw std::runtime_error(file + ": FIX " + std::to_string(id) + ": no such node");
  for (const auto& [ids, edge] : g.edges)
    for (const auto id : {ids.first, ids.second})
      if (!g.nodes.count(id))
        throw std::runtime_error(
            file + ": EDGE3 " + std::to_string(ids.first) + " " + std::to_string(ids.second) +
            ": no node " + std::to_string(id));
  return g;
}
}  // namespace roislam::io
