/* Fuzz target: camera calibration files, MRPT TCamera ini and ROS / MRPT
 * yaml (resolveCamera). The first byte chooses the format. */
#include <roislam/io/CameraPresets.h>

#include <cstdio>
#include <cstdlib>

#include "FuzzSupport.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  if (size == 0)
    return 0;
  const bool yaml = data[0] & 1;
  const std::string file =
      roislam::fuzz::writeScratch(yaml ? "cam.yaml" : "cam.ini", data + 1, size - 1);
  try
  {
    const auto cam = roislam::io::resolveCamera(file, roislam::fuzz::scratchDir().string());
    // Accepted calibrations are usable: a positive size and focal length.
    if (cam.ncols == 0 || cam.nrows == 0 || !(cam.fx() > 0) || !(cam.fy() > 0))
    {
      std::fprintf(stderr, "unusable camera accepted\n");
      std::abort();
    }
  }
  catch (const std::exception& e)
  {
    roislam::fuzz::checkRejection(e, file);
  }
  return 0;
}
