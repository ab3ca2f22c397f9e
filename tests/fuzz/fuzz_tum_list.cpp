/* Fuzz target: TUM lists (rgb.txt / depth.txt), the association and the
 * image reading behind them (CTumFrameSource). The input is both lists; a
 * line naming "rgb.txt" makes the reader decode the input as an image. */
#include <roislam/io/CTumFrameSource.h>
#include <roislam/io/CameraPresets.h>

#include <filesystem>

#include "FuzzSupport.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  namespace fs = std::filesystem;
  const fs::path dir = roislam::fuzz::scratchDir() / "tum";
  fs::create_directories(dir / "rgb");
  fs::create_directories(dir / "depth");
  roislam::fuzz::writeScratch("tum/rgb.txt", data, size);
  roislam::fuzz::writeScratch("tum/depth.txt", data, size);
  static const auto camera = roislam::io::cameraPreset("fr1");
  try
  {
    roislam::io::CTumFrameSource source(dir.string(), camera);
    for (int i = 0; i < 3 && source.next(); ++i)
    {
    }
  }
  catch (const std::exception& e)
  {
    // Every error names a file: a list (with its line) or an image.
    roislam::fuzz::checkRejection(e, "/");
  }
  return 0;
}
