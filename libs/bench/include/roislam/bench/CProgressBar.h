/* A one-line progress bar with ETA for roi-bench, redrawn in place on a
 * terminal stream (stderr): "[#####.....] 12/40 (1 failed, 3 skipped) 05:12
 * elapsed, ETA 14:30  <last run id>". Fed by CBenchRunner's progress callback.
 */
#pragma once

#include <roislam/bench/CBenchRunner.h>

#include <ostream>
#include <string>

namespace roislam::bench
{
class CProgressBar
{
 public:
  explicit CProgressBar(std::ostream& out, int width = 30) : m_out(out), m_width(width) {}
  /** The line for a progress state (no carriage return). */
  std::string format(const CBenchRunner::TProgress& p) const;
  /** Redraws the line; ends it with a newline when all runs are done. */
  void update(const CBenchRunner::TProgress& p);
  /** "mm:ss" or "h:mm:ss". */
  static std::string duration(double seconds);

 private:
  std::ostream& m_out;
  int m_width;
};
}  // namespace roislam::bench
