/* Fuzz target: the rawlog reader (CRawlogFrameSource: MRPT deserialisation,
 * our own object loop, the conversion of each observation to a frame). */
#include <roislam/io/CRawlogFrameSource.h>

#include "FuzzSupport.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  const std::string file = roislam::fuzz::writeScratch("fuzz.rawlog", data, size);
  try
  {
    roislam::io::CRawlogFrameSource source(file);
    for (int i = 0; i < 4 && source.next(); ++i)
    {
    }
  }
  catch (const std::exception& e)
  {
    roislam::fuzz::checkRejection(e, file);
  }
  return 0;
}
