#include "roislam/evaluation/CTrajectoryPlot.h"

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>

#include "Gnuplot.h"

namespace roislam::evaluation
{
namespace fs = std::filesystem;
using gnuplot::quoted;

namespace
{
int chooseUpAxis(const std::string& setting, const io::TTrajectory& reference)
{
  if (setting == "x")
    return 0;
  if (setting == "y")
    return 1;
  if (setting == "z")
    return 2;
  if (setting != "auto")
    throw std::invalid_argument(
        "CTrajectoryPlot: up_axis must be auto, x, y or z, not '" + setting + "'");
  return CTrajectoryPlot::autoUpAxis(reference);
}

/** Columns: time since t0, x, y, z; a blank line (gnuplot: break the line)
 *  wherever consecutive stamps are more than gapBreak apart. */
void writeData(const fs::path& file, const io::TTrajectory& trajectory, double t0, double gapBreak)
{
  io::TTrajectory sorted = trajectory;
  std::stable_sort(
      sorted.begin(), sorted.end(),
      [](const auto& a, const auto& b) { return a.timestamp < b.timestamp; });
  std::ofstream out(file);
  out.precision(17);
  for (std::size_t k = 0; k < sorted.size(); ++k)
  {
    if (k > 0 && sorted[k].timestamp - sorted[k - 1].timestamp > gapBreak)
      out << "\n";
    const auto& p = sorted[k].pose;
    out << sorted[k].timestamp - t0 << ' ' << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  }
  if (!out)
    throw std::runtime_error("cannot write plot data " + file.string());
}

}  // namespace

int CTrajectoryPlot::autoUpAxis(const io::TTrajectory& cameraPoses)
{
  if (cameraPoses.empty())
    return 2;
  std::array<double, 3> alongX{}, alongY{};
  for (const auto& p : cameraPoses)
  {
    const auto R = p.pose.getRotationMatrix();
    for (int a = 0; a < 3; ++a)
    {
      alongX[a] += std::abs(R(a, 0));
      alongY[a] += std::abs(R(a, 1));
    }
  }
  const double n = static_cast<double>(cameraPoses.size());
  const double least = std::min({alongX[0], alongX[1], alongX[2]}) / n;
  int best = -1;
  for (int a : {2, 0, 1})  // z first: preferred on exact ties
  {
    if (alongX[a] / n > least + 0.1)
      continue;
    if (best < 0 || alongY[a] > alongY[best] + 1e-9 * n)
      best = a;
  }
  return best;
}

CTrajectoryPlot::CTrajectoryPlot() : CTrajectoryPlot(TOptions()) {}

CTrajectoryPlot::CTrajectoryPlot(const TOptions& options) : m_options(options)
{
  if (m_options.width <= 0 || m_options.height <= 0)
    throw std::invalid_argument("CTrajectoryPlot: width and height must be > 0");
  if (!(m_options.gap_break > 0))
    throw std::invalid_argument("CTrajectoryPlot: gap_break must be > 0 s");
  chooseUpAxis(m_options.up_axis, {});  // validates the name
}

namespace
{
// -------------------------------------------------------------- plot stages

/** Ground truth if any, else the first non-empty estimate: it fixes the up
 *  axis and the time origin. */
const io::TTrajectory& plotReference(
    const std::string& pngFile, const io::TTrajectory& groundTruth,
    const std::vector<CTrajectoryPlot::TNamedTrajectory>& estimates)
{
  const io::TTrajectory* reference = groundTruth.empty() ? nullptr : &groundTruth;
  for (const auto& e : estimates)
    if (!reference && !e.second.empty())
      reference = &e.second;
  if (!reference)
    throw std::runtime_error(pngFile + ": nothing to plot (all trajectories empty)");
  return *reference;
}

struct TPlotAxes
{
  explicit TPlotAxes(int upAxis) : up(upAxis) {}
  int up;
  int h1 = up == 0 ? 1 : 0;  // top-view horizontal axis
  int h2 = up == 2 ? 1 : 2;  // top-view vertical axis
};

std::string column(int axis)
{
  return std::to_string(axis + 2);
}

double earliestStamp(const io::TTrajectory& trajectory)
{
  double t0 = std::numeric_limits<double>::infinity();
  for (const auto& p : trajectory)
    t0 = std::min(t0, p.timestamp);
  return t0;
}

/** The gnuplot "plot" entries of both panels, one per series. */
struct TPlotSeries
{
  std::vector<std::string> top, height;
};

/** What every series' data file and entries share. */
struct TSeriesContext
{
  fs::path dir;
  double t0;
  double gapBreak;
  TPlotAxes axes;
};

void addSeries(
    TPlotSeries& series, const TSeriesContext& ctx, const io::TTrajectory& t,
    const std::string& title, const std::string& colour, int width, std::size_t idx)
{
  const std::string style = " with lines lw " + std::to_string(width) + " lc rgb '" + colour + "'";
  if (t.empty())
  {
    const std::string entry = "keyentry" + style + " title " + quoted(title + " (no trajectory)");
    series.top.push_back(entry);
    series.height.push_back(entry);
    return;
  }
  const fs::path data = ctx.dir / ("series" + std::to_string(idx) + ".dat");
  writeData(data, t, ctx.t0, ctx.gapBreak);
  const std::string f = quoted(data.string());
  series.top.push_back(
      f + " using " + column(ctx.axes.h1) + ":" + column(ctx.axes.h2) + style + " title " +
      quoted(title));
  series.height.push_back(
      f + " using 1:" + column(ctx.axes.up) + style + " title " + quoted(title));
}

TPlotSeries writeAllSeries(
    const TSeriesContext& ctx, const io::TTrajectory& groundTruth,
    const std::vector<CTrajectoryPlot::TNamedTrajectory>& estimates)
{
  const std::array<const char*, 8> colours = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e",
                                              "#9467bd", "#8c564b", "#e377c2", "#17becf"};
  TPlotSeries series;
  if (!groundTruth.empty())
    addSeries(series, ctx, groundTruth, "ground truth", "#000000", 3, 0);
  for (std::size_t k = 0; k < estimates.size(); ++k)
    addSeries(
        series, ctx, estimates[k].second, estimates[k].first, colours[k % colours.size()], 2,
        k + 1);
  return series;
}

void writeScript(
    const fs::path& script, const fs::path& image, const CTrajectoryPlot::TOptions& options,
    const TPlotAxes& axes, const TPlotSeries& series)
{
  const std::array<const char*, 3> names = {"x", "y", "z"};
  const int h1 = axes.h1, h2 = axes.h2, up = axes.up;
  std::ofstream gp(script);
  gp << gnuplot::pngTerminal(options.width, options.height, image)
     << "set grid\nset key top left box opaque\n"
     << "set multiplot layout 1,2 title " << quoted(options.title) << "\n"
     << "set title " << quoted(std::string("top view (") + names[h1] + "-" + names[h2] + ")")
     << "\nset xlabel " << quoted(std::string(names[h1]) + " [m]") << "\nset ylabel "
     << quoted(std::string(names[h2]) + " [m]") << "\nset size ratio -1\n";
  gp << "plot ";
  for (std::size_t k = 0; k < series.top.size(); ++k)
    gp << (k ? ", \\\n  " : "") << series.top[k];
  gp << "\nset size noratio\nset title "
     << quoted(std::string("height (") + names[up] + ") over time")
     << "\nset xlabel 'time [s]'\nset ylabel " << quoted(std::string(names[up]) + " [m]") << "\n";
  gp << "plot ";
  for (std::size_t k = 0; k < series.height.size(); ++k)
    gp << (k ? ", \\\n  " : "") << series.height[k];
  gp << "\nunset multiplot\nset output\n";
  if (!gp)
    throw std::runtime_error("cannot write the gnuplot script " + script.string());
}
}  // namespace

void CTrajectoryPlot::plot(
    const std::string& pngFile, const io::TTrajectory& groundTruth,
    const std::vector<TNamedTrajectory>& estimates) const
{
  const io::TTrajectory& reference = plotReference(pngFile, groundTruth, estimates);
  const TPlotAxes axes(chooseUpAxis(m_options.up_axis, reference));

  gnuplot::TTempDir tmp;
  const TSeriesContext ctx{tmp.path, earliestStamp(reference), m_options.gap_break, axes};
  const TPlotSeries series = writeAllSeries(ctx, groundTruth, estimates);

  const fs::path image = tmp.path / "figure.png";
  const fs::path script = tmp.path / "figure.gp";
  writeScript(script, image, m_options, axes, series);

  gnuplot::renderPng(m_options.gnuplot, script, image, pngFile);
}
}  // namespace roislam::evaluation
