/* MRPT 2.5.8 work-around: mrpt::aligned_allocator_cpp11::allocate() returns
 * mrpt::aligned_malloc()'s null on failure instead of throwing, so the
 * std::vector behind an MRPT matrix writes through a null pointer: a corrupt
 * rawlog whose range image claims 10^9 x 10^9 pixels crashed the reader
 * (found by fuzz_rawlog, tests/fuzz/regressions/rawlog/absurd-matrix-size).
 * This definition replaces MRPT's for the whole process (the executable's
 * symbol wins over libmrpt-core's): the same rounding and aligned_alloc, but
 * a failure (or a size that overflows the rounding) throws std::bad_alloc,
 * which the rawlog reader reports as a corrupt file. aligned_free (free) is
 * unchanged and matches.
 */
#include <cstddef>
#include <cstdlib>
#include <limits>
#include <new>

namespace mrpt
{
void* aligned_malloc(std::size_t size, std::size_t alignment);

void* aligned_malloc(std::size_t size, std::size_t alignment)
{
  // aligned_alloc wants a multiple of the alignment (MRPT rounds the same way).
  if (alignment != 0 && size % alignment != 0)
  {
    if (size / alignment + 1 > std::numeric_limits<std::size_t>::max() / alignment)
      throw std::bad_alloc();
    size = (size / alignment + 1) * alignment;
  }
  void* p = std::aligned_alloc(alignment, size);
  if (!p && size != 0)
    throw std::bad_alloc();
  return p;
}
}  // namespace mrpt

namespace roislam::io::detail
{
/** Referenced by the rawlog reader so that this object file is linked into
 *  every program that reads rawlogs (it is in a static library). */
void linkThrowingAlignedMalloc() {}
}  // namespace roislam::io::detail
