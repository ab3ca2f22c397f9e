/* Fuzz target: pose-graph text files (loadGraphText), and the exact
 * save/load round trip of what was accepted: the same nodes, and the same
 * edges with the same information, entry for entry. */
#include <roislam/io/GraphText.h>

#include <cstdio>
#include <cstdlib>

#include "FuzzSupport.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  using roislam::io::loadGraphText;
  const std::string file = roislam::fuzz::writeScratch("graph.graph", data, size);
  mrpt::graphs::CNetworkOfPoses3DInf g;
  try
  {
    g = loadGraphText(file);
  }
  catch (const std::exception& e)
  {
    roislam::fuzz::checkRejection(e, file);
    return 0;
  }
  const std::string copy = (roislam::fuzz::scratchDir() / "graph_copy.graph").string();
  roislam::io::saveGraphText(g, copy);
  const auto back = loadGraphText(copy);
  if (back.nodes.size() != g.nodes.size() || back.edges.size() != g.edges.size())
  {
    std::fprintf(
        stderr, "round trip: %zu nodes, %zu edges -> %zu, %zu\n", g.nodes.size(), g.edges.size(),
        back.nodes.size(), back.edges.size());
    std::abort();
  }
  // Edges between the same two nodes keep their order (a multimap, written
  // and read in order).
  auto b = back.edges.cbegin();
  for (auto a = g.edges.cbegin(); a != g.edges.cend(); ++a, ++b)
  {
    bool same = a->first == b->first;
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c < 6; ++c)
        same = same && a->second.cov_inv(r, c) == b->second.cov_inv(r, c);
    if (!same)
    {
      std::fprintf(
          stderr, "round trip changed edge %lu-%lu\n", static_cast<unsigned long>(a->first.first),
          static_cast<unsigned long>(a->first.second));
      std::abort();
    }
  }
  return 0;
}
