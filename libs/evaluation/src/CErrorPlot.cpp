#include "roislam/evaluation/CErrorPlot.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "Gnuplot.h"

namespace roislam::evaluation
{
namespace fs = std::filesystem;
using gnuplot::quoted;

CErrorPlot::CErrorPlot() : CErrorPlot(TOptions()) {}

CErrorPlot::CErrorPlot(const TOptions& options) : m_options(options)
{
  if (m_options.width <= 0 || m_options.height <= 0)
    throw std::invalid_argument("CErrorPlot: width and height must be > 0");
}

void CErrorPlot::plot(const std::string& pngFile, const TEvaluationResult& result) const
{
  const auto& ate = result.ate.samples;
  const auto& rpe = result.rpe.samples;
  if (ate.empty() && rpe.empty())
    throw std::runtime_error(pngFile + ": nothing to plot (the evaluation has no samples)");
  const double t0 = std::min(
      ate.empty() ? rpe.front().timestamp : ate.front().timestamp,
      rpe.empty() ? ate.front().timestamp : rpe.front().timestamp);
  const double t1 = std::max(
      ate.empty() ? rpe.back().timestamp : ate.back().timestamp,
      rpe.empty() ? ate.back().timestamp : rpe.back().timestamp);

  gnuplot::TTempDir tmp;
  const fs::path ateData = tmp.path / "ate.dat", rpeData = tmp.path / "rpe.dat";
  {
    std::ofstream a(ateData), r(rpeData);
    a.precision(10);
    r.precision(10);
    for (const auto& s : ate)
      a << s.timestamp - t0 << ' ' << s.error << '\n';
    for (const auto& s : rpe)
      r << s.timestamp - t0 << ' ' << s.trans << ' ' << s.rot_deg << '\n';
    if (!a || !r)
      throw std::runtime_error("cannot write plot data in " + tmp.path.string());
  }

  char figures[160];
  std::snprintf(
      figures, sizeof figures, "ATE RMSE %.4f m (%zu poses)", result.ate.rmse, result.ate.pairs);
  char rpeTitle[160];
  std::snprintf(
      rpeTitle, sizeof rpeTitle, "RPE RMSE %.4f m / %.2f deg (%zu pairs)", result.rpe.trans_rmse,
      result.rpe.rot_rmse_deg, result.rpe.pairs);

  const fs::path image = tmp.path / "errors.png";
  const fs::path script = tmp.path / "errors.gp";
  {
    std::ofstream gp(script);
    gp << gnuplot::pngTerminal(m_options.width, m_options.height, image)
       << "set grid\nset key top left box opaque\nset xlabel 'time [s]'\n"
       << "set xrange [0:" << std::max(t1 - t0, 1e-3) << "]\n"
       << "set multiplot layout 2,1 title " << quoted(m_options.title) << "\n";
    // Both panels share the time axis, so stretches line up.
    gp << "set title " << quoted("absolute trajectory error over time: " + std::string(figures))
       << "\nset ylabel 'ATE [m]'\nset yrange [0:*]\n"
       << "plot " << quoted(ateData.string())
       << " using 1:2 with lines lw 2 lc rgb '#1f77b4' title 'error after alignment', \\\n"
       << "  " << result.ate.rmse << " with lines dt 2 lw 2 lc rgb '#1f77b4' title 'RMSE'\n";
    gp << "set title " << quoted("relative pose error over time: " + std::string(rpeTitle))
       << "\nset ylabel 'translation [m]'\nset y2label 'rotation [deg]'\n"
       << "set ytics nomirror\nset y2tics\nset y2range [0:*]\n"
       << "plot " << quoted(rpeData.string())
       << " using 1:2 axes x1y1 with lines lw 2 lc rgb '#d62728' title 'translation', \\\n"
       << "  " << quoted(rpeData.string())
       << " using 1:3 axes x1y2 with lines lw 2 lc rgb '#2ca02c' title 'rotation'\n"
       << "unset multiplot\nset output\n";
    if (!gp)
      throw std::runtime_error("cannot write the gnuplot script " + script.string());
  }
  gnuplot::renderPng(m_options.gnuplot, script, image, pngFile);
}
}  // namespace roislam::evaluation
