/* Timing for the paired cost measurements (CPairedSlamCost, roislam-stage-bench):
 * the process's CPU time and a wrapper that adds a call's wall-clock and CPU
 * milliseconds to running sums.
 */
#pragma once

#include <time.h>

#include <chrono>

namespace roislam::bench
{
/** CPU time of the whole process (all OpenCV worker threads), ms: a cost
 *  figure that, unlike wall time, does not grow when other programs share the
 *  cores. */
inline double processCpuMs()
{
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
}

/** Runs f, adding its wall-clock and process-CPU milliseconds to the sums. */
template <class F>
void timed(F&& f, double& wallMs, double& cpuMs)
{
  const double cpu0 = processCpuMs();
  const auto t0 = std::chrono::steady_clock::now();
  f();
  wallMs +=
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  cpuMs += processCpuMs() - cpu0;
}
}  // namespace roislam::bench
