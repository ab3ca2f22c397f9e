/* Stage timing of the front end (per-frame milliseconds in TFrameResult). */
#pragma once

#include <chrono>

namespace roislam::frontend::detail
{
using Clock = std::chrono::steady_clock;

inline double msSince(Clock::time_point t0)
{
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}
}  // namespace roislam::frontend::detail
