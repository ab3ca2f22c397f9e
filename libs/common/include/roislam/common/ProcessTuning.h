/* Process-wide settings the image-heavy apps apply once at start-up. */
#pragma once

namespace roislam::common
{
/** Keeps large, short-lived buffers (image pyramids, decoded PNGs: 1-20 MB
 *  each, allocated and freed every frame) on the heap instead of letting
 *  glibc mmap/munmap them per allocation. With glibc's defaults every frame
 *  paid fresh page faults for those buffers: measured on fr1/rpy with SIFT,
 *  roi-graphslam spent 6 of 27 s in the kernel and ran at 9.9 fps; with this
 *  setting 0.7 s and 16.9 fps, same peak memory. No-op on other C libraries. */
void tuneAllocatorForImages();
}  // namespace roislam::common
