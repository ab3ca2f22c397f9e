/* Fuzz target: TUM trajectory files (loadTumTrajectory, both treatments of
 * invalid poses), and the exact save/load round trip of what was accepted. */
#include <roislam/io/TumTrajectory.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "FuzzSupport.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  using namespace roislam::io;
  const std::string file = roislam::fuzz::writeScratch("traj.txt", data, size);
  for (const auto invalid : {EInvalidPose::Reject, EInvalidPose::Skip})
  {
    TTrajectory t;
    try
    {
      t = loadTumTrajectory(file, invalid);
    }
    catch (const std::exception& e)
    {
      roislam::fuzz::checkRejection(e, file);
      continue;
    }
    for (const auto& p : t)
      if (!std::isfinite(p.timestamp) || !std::isfinite(p.pose.x()))
      {
        std::fprintf(stderr, "non-finite pose accepted\n");
        std::abort();
      }
    // What was read writes back and reads again to the same stamps.
    const std::string copy = (roislam::fuzz::scratchDir() / "traj_copy.txt").string();
    saveTumTrajectory(copy, t);
    const auto back = loadTumTrajectory(copy);
    if (back.size() != t.size())
    {
      std::fprintf(stderr, "round trip lost poses: %zu -> %zu\n", t.size(), back.size());
      std::abort();
    }
    for (std::size_t i = 0; i < t.size(); ++i)
      if (back[i].timestamp != t[i].timestamp)
        std::abort();
  }
  return 0;
}
