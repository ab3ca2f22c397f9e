#include "roislam/bench/CProgressBar.h"

#include <cstdio>

namespace roislam::bench
{
std::string CProgressBar::duration(double seconds)
{
  const long s = seconds < 0 ? 0 : static_cast<long>(seconds + 0.5);
  char buf[32];
  if (s >= 3600)
    std::snprintf(buf, sizeof(buf), "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  else
    std::snprintf(buf, sizeof(buf), "%02ld:%02ld", s / 60, s % 60);
  return buf;
}

std::string CProgressBar::format(const CBenchRunner::TProgress& p) const
{
  const int filled =
      p.total ? static_cast<int>(m_width * static_cast<double>(p.done) / p.total) : m_width;
  std::string line = "[" + std::string(filled, '#') + std::string(m_width - filled, '.') + "] " +
                     std::to_string(p.done) + "/" + std::to_string(p.total);
  if (p.failed || p.skipped)
    line += " (" + std::to_string(p.failed) + " failed, " + std::to_string(p.skipped) +
            " already done)";
  line += " " + duration(p.elapsedS) + " elapsed";
  if (p.done < p.total)
    line += ", ETA " + (p.etaS ? duration(*p.etaS) : std::string("?"));
  if (!p.lastId.empty())
    line += "  " + p.lastId;
  return line;
}

void CProgressBar::update(const CBenchRunner::TProgress& p)
{
  m_out << "\r" << format(p) << "\033[K";
  if (p.done >= p.total)
    m_out << "\n";
  m_out.flush();
}
}  // namespace roislam::bench
