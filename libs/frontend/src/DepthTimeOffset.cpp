#include "DepthTimeOffset.h"

#include <roislam/common/Median.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace roislam::frontend::detail
{
namespace
{
// About a second of frames at 30 Hz: long enough to outvote the stamps'
// jitter, short enough to follow the two cameras' clocks drifting apart.
constexpr std::size_t kWindow = 30;

/** x wrapped into [-p/2, p/2). */
double wrap(double x, double p)
{
  return x - p * std::floor(x / p + 0.5);
}
}  // namespace

void CDepthTimeOffset::reset()
{
  m_intervals.clear();
  m_differences.clear();
  m_haveLast = false;
}

double CDepthTimeOffset::period() const
{
  return m_intervals.empty()
             ? 0.0
             : common::upperMedian(std::vector<double>(m_intervals.begin(), m_intervals.end()));
}

double CDepthTimeOffset::update(double colourStamp, double depthStamp)
{
  const double diff = depthStamp - colourStamp;
  if (m_haveLast && colourStamp > m_lastColour)
  {
    m_intervals.push_back(colourStamp - m_lastColour);
    if (m_intervals.size() > kWindow)
      m_intervals.pop_front();
  }
  m_lastColour = colourStamp;
  m_haveLast = true;
  m_differences.push_back(diff);
  if (m_differences.size() > kWindow)
    m_differences.pop_front();
  const double p = period();
  if (!(p > 0))
    return diff;  // the first frame: its own stamps are all there is
  // Circular median of the phases: centred on their circular mean, the
  // median of the deviations (within half a period of it).
  double s = 0, c = 0;
  for (double d : m_differences)
  {
    s += std::sin(2 * M_PI * d / p);
    c += std::cos(2 * M_PI * d / p);
  }
  const double mean = std::atan2(s, c) * p / (2 * M_PI);
  std::vector<double> dev;
  dev.reserve(m_differences.size());
  for (double d : m_differences)
    dev.push_back(wrap(d - mean, p));
  const double phase = mean + common::upperMedian(dev);
  // The frame's depth image is the one the stamps say (before or after its
  // colour image), at the estimated phase.
  return phase + p * std::round((diff - phase) / p);
}
}  // namespace roislam::frontend::detail
