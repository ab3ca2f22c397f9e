#include "roislam/io/CFrameClock.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace roislam::io
{
namespace
{
// Three seconds of frames: long enough that the fitted line's error at its
// newest end (about 2 sigma / sqrt(N)) is a few tenths of a millisecond for
// fr1's 1.1-1.9 ms of jitter, short enough to follow a clock's drift.
constexpr double kWindowSeconds = 3.0;
// Fewer slots than this fit the offset alone, at the nominal period: a
// slope from a handful of jittered stamps is worse than the nominal one.
constexpr std::size_t kMinSlotsForSlope = 10;
// A stamp further than this share of a period from its slot is not a
// jittered stamp of a regular clock (fr1's lie within 0.15 periods of the
// causal fit: 4.9 ms on fr1/rpy)...
constexpr double kMaxDeviationPeriods = 0.2;
// ...nor are stamps that scatter around their line by more than this RMS
// (fr1's: 0.03-0.06 periods; a 20 Hz camera read as 30 Hz, one slot in three
// empty: 0.2). Their frames keep their stamps until the scatter falls.
constexpr double kMaxRmsPeriods = 0.08;
constexpr double kMaxRateError = 0.05;
// A clock times frames once this many stamps agree with it: two or three
// stamps fit a wrong period too (a 20 Hz camera described as 30 Hz).
constexpr std::size_t kMinSlotsToTime = 5;
constexpr double kMaxGapSeconds = 1.0;
constexpr double kStampResolution = 1e-6;
}  // namespace

nlohmann::json toJson(const TFrameClockStats& stats)
{
  return {
      {"frames", stats.frames},
      {"clocked", stats.clocked},
      {"restarts", stats.restarts},
      {"rms_correction_ms", stats.rmsCorrectionMs},
      {"max_correction_ms", stats.maxCorrectionMs}};
}

CFrameClock::CFrameClock(double frameRate)
{
  if (!(frameRate > 0) || !std::isfinite(frameRate))
    throw std::invalid_argument("CFrameClock: frame rate must be positive");
  m_period = 1.0 / frameRate;
  m_window = std::max<std::size_t>(kMinSlotsForSlope, std::lround(kWindowSeconds * frameRate));
}

void CFrameClock::reset()
{
  m_slots.clear();
  m_stats = {};
  m_sumSq = 0;
  m_lastTime = 0;
}

void CFrameClock::restart(double stamp)
{
  m_slots.clear();
  m_anchor = stamp;
  m_slots.push_back({0, 0.0});
  m_lastTime = stamp;
}

void CFrameClock::fit(double& a, double& b) const
{
  const double count = static_cast<double>(m_slots.size());
  double mn = 0, mt = 0;
  for (const auto& s : m_slots)
  {
    mn += static_cast<double>(s.n);
    mt += s.t;
  }
  mn /= count;
  mt /= count;
  b = m_period;
  if (m_slots.size() >= kMinSlotsForSlope)
  {
    double snn = 0, snt = 0;
    for (const auto& s : m_slots)
    {
      const double dn = static_cast<double>(s.n) - mn;
      snn += dn * dn;
      snt += dn * (s.t - mt);
    }
    if (snn > 0)
      b = snt / snn;
  }
  a = mt - b * mn;
}

double CFrameClock::time(double stamp)
{
  ++m_stats.frames;
  if (!std::isfinite(stamp))
    return stamp;
  if (m_slots.empty())
  {
    restart(stamp);
    return stamp;
  }
  double a = 0, b = 0;
  fit(a, b);
  const double rel = stamp - m_anchor;
  const double slot = std::round((rel - a) / b);
  const std::int64_t last = m_slots.back().n;
  if (!std::isfinite(slot) || slot <= static_cast<double>(last) ||
      (slot - static_cast<double>(last)) * m_period > kMaxGapSeconds)
  {
    ++m_stats.restarts;
    restart(stamp);
    return stamp;
  }
  const auto n = static_cast<std::int64_t>(slot);
  m_slots.push_back({n, rel});
  while (m_slots.size() > m_window)
    m_slots.pop_front();
  fit(a, b);
  const double onClock = a + b * static_cast<double>(n);
  const double deviation = rel - onClock;
  // Below a microsecond (TUM's and MRPT's stamp resolution) a stamp is on
  // its clock already: regular stamps, a render's, come back bit for bit.
  const double out = std::abs(deviation) < kStampResolution ? stamp : m_anchor + onClock;
  if (std::abs(b / m_period - 1) > kMaxRateError ||
      std::abs(deviation) > kMaxDeviationPeriods * m_period || !(out > m_lastTime))
  {
    ++m_stats.restarts;
    restart(stamp);
    return stamp;
  }
  double scatter = 0;
  for (const auto& s : m_slots)
    scatter += std::pow(s.t - a - b * static_cast<double>(s.n), 2);
  scatter = std::sqrt(scatter / static_cast<double>(m_slots.size()));
  if (m_slots.size() < kMinSlotsToTime || scatter > kMaxRmsPeriods * m_period)
  {
    m_lastTime = stamp;
    return stamp;
  }
  ++m_stats.clocked;
  m_sumSq += deviation * deviation;
  m_stats.rmsCorrectionMs = 1e3 * std::sqrt(m_sumSq / static_cast<double>(m_stats.clocked));
  m_stats.maxCorrectionMs = std::max(m_stats.maxCorrectionMs, 1e3 * std::abs(deviation));
  m_lastTime = out;
  return out;
}
}  // namespace roislam::io
