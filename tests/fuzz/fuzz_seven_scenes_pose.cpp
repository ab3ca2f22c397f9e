/* Fuzz target: 7-Scenes pose files (frame-NNNNNN.pose.txt, a 4x4 matrix;
 * loadSevenScenesGroundTruth): a rejected one is named in one line; an
 * accepted one is a finite rigid pose, and the TUM file the reader makes of
 * it reads back (what every app takes as the ground truth). */
#include <roislam/io/SevenScenes.h>
#include <roislam/io/TumTrajectory.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "FuzzSupport.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  using namespace roislam::io;
  TSevenScenesFrame frame;
  frame.number = 3;
  frame.poseFile = roislam::fuzz::writeScratch("frame-000003.pose.txt", data, size);
  TTrajectory gt;
  try
  {
    gt = loadSevenScenesGroundTruth({frame}, 30.0, mrpt::poses::CPose3D(-0.025, 0, 0, 0.01, 0, 0));
  }
  catch (const std::exception& e)
  {
    roislam::fuzz::checkRejection(e, frame.poseFile);
    return 0;
  }
  if (gt.size() > 1)
    std::abort();
  for (const auto& p : gt)
  {
    const auto R = p.pose.getRotationMatrix();
    const double det = R.det();
    if (!std::isfinite(p.pose.x()) || !std::isfinite(p.pose.y()) || !std::isfinite(p.pose.z()) ||
        !(std::abs(det - 1) < 1e-6) || p.timestamp != 0.1)
    {
      std::fprintf(stderr, "accepted a pose that is not finite and rigid (det %g)\n", det);
      std::abort();
    }
    const std::string copy = (roislam::fuzz::scratchDir() / "gt.txt").string();
    saveTumTrajectory(copy, gt);
    if (loadTumTrajectory(copy).size() != 1)
      std::abort();
  }
  return 0;
}
