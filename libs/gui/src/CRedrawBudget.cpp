#include "roislam/gui/CRedrawBudget.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace roislam::gui
{
namespace
{
/** The budget is judged over at least this much of the rest's CPU (s), so
 *  that the 10 ms clock ticks of /proc do not make it jump. */
constexpr double kMinWindowCpuS = 0.5;

double ticksToSeconds(long long ticks)
{
  static const double hz = static_cast<double>(sysconf(_SC_CLK_TCK));
  return ticks / hz;
}

/** utime + stime of one /proc/<pid>/task/<tid>/stat, and the thread's name. */
bool readThreadStat(const std::filesystem::path& stat, std::string& name, long long& ticks)
{
  std::ifstream f(stat);
  std::string line;
  if (!std::getline(f, line))
    return false;
  // "tid (name) state ..." : the name may hold spaces and parentheses.
  const auto open = line.find('('), close = line.rfind(')');
  if (open == std::string::npos || close == std::string::npos || close < open)
    return false;
  name = line.substr(open + 1, close - open - 1);
  std::istringstream rest(line.substr(close + 2));
  std::string field;
  long long utime = 0, stime = 0;
  // Fields after the name: state(3) ... utime(14) stime(15).
  for (int i = 3; i <= 15 && rest >> field; ++i)
  {
    if (i == 14)
      utime = std::stoll(field);
    if (i == 15)
      stime = std::stoll(field);
  }
  ticks = utime + stime;
  return true;
}
}  // namespace

CRedrawBudget::CRedrawBudget(double minPeriodS, double maxPeriodS, double share)
    : m_minPeriod(minPeriodS),
      m_maxPeriod(std::max(minPeriodS, maxPeriodS)),
      m_share(share),
      m_period(minPeriodS)
{
}

double CRedrawBudget::update(double viewCpuS, double processCpuS)
{
  if (!m_started)
  {
    m_started = true;
    m_lastView = viewCpuS;
    m_lastProcess = processCpuS;
    return m_period;
  }
  const double view = viewCpuS - m_lastView;
  const double rest = (processCpuS - m_lastProcess) - view;
  if (rest < kMinWindowCpuS)
    return m_period;  // too little to judge (or SLAM paused / finished)
  const double ratio = view / rest;
  if (ratio > m_share)
    m_period = std::min(m_maxPeriod, m_period * std::min(2.0, ratio / m_share));
  else if (ratio < 0.7 * m_share)
    m_period = std::max(m_minPeriod, m_period * 0.8);
  m_lastView = viewCpuS;
  m_lastProcess = processCpuS;
  return m_period;
}

std::pair<double, double> threadCpuSeconds(const std::vector<std::string>& names)
{
  long long matched = 0;
  std::error_code ec;
  for (const auto& task : std::filesystem::directory_iterator("/proc/self/task", ec))
  {
    std::string name;
    long long ticks = 0;
    if (!readThreadStat(task.path() / "stat", name, ticks))
      continue;
    const bool ours = std::any_of(
        names.begin(), names.end(),
        [&](const std::string& n)
        {
          return n.find(':') != std::string::npos ? name.find(n) != std::string::npos
                                                  : name.rfind(n, 0) == 0;
        });
    if (ours)
      matched += ticks;
  }
  struct rusage ru
  {
  };
  getrusage(RUSAGE_SELF, &ru);
  const double process = ru.ru_utime.tv_sec + ru.ru_utime.tv_usec * 1e-6 + ru.ru_stime.tv_sec +
                         ru.ru_stime.tv_usec * 1e-6;
  return {ticksToSeconds(matched), process};
}
}  // namespace roislam::gui
