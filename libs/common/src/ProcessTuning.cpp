#include "roislam/common/ProcessTuning.h"

#include <cstdlib>  // defines __GLIBC__ when the C library is glibc

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace roislam::common
{
void tuneAllocatorForImages()
{
#if defined(__GLIBC__)
  // Allocations below 32 MiB (glibc's maximum for this setting on 64-bit;
  // larger values are rejected) come from the heap; freed memory is returned
  // to the system only beyond 256 MiB of slack at the heap's top.
  mallopt(M_MMAP_THRESHOLD, 32 * 1024 * 1024);
  mallopt(M_TRIM_THRESHOLD, 256 * 1024 * 1024);
#endif
}
}  // namespace roislam::common
