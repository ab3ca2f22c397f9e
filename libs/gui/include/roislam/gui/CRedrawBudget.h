/* Keeps the live view out of the SLAM run's way on any machine: the view
 * redraws at most refresh_hz times a second, and less when its threads
 * (the drawing thread, MRPT's wx thread, the GL driver's) used more CPU
 * than `share` times what the rest of the process (the SLAM threads) used
 * over the last second or more. Under Xvfb (Mesa's software GL) a redraw of
 * a 1024 x 576 window costs about 30 ms of CPU, so a fixed rate costs the
 * run more the slower the machine runs it (a loaded machine gives SLAM
 * less CPU per second, the view the same); the budget ties the view's cost
 * to the run's instead. Used by CLiveView's drawing thread.
 */
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace roislam::gui
{
class CRedrawBudget
{
 public:
  /** Periods in seconds (min = 1 / refresh_hz); share in (0, 1]. */
  CRedrawBudget(double minPeriodS, double maxPeriodS, double share);

  /** After a redraw: the CPU seconds used so far (cumulative) by the view's
   *  threads and by the whole process. Returns the period to wait now. */
  double update(double viewCpuS, double processCpuS);
  double period() const { return m_period; }

 private:
  double m_minPeriod, m_maxPeriod, m_share;
  double m_period;
  bool m_started = false;
  double m_lastView = 0, m_lastProcess = 0;
};

/** Cumulative CPU seconds of this process's threads whose name starts with
 *  (or, for names with a ':', contains) one of `names`, and of the whole
 *  process. Linux (/proc/self/task); zeros elsewhere. */
std::pair<double, double> threadCpuSeconds(const std::vector<std::string>& names);
}  // namespace roislam::gui
