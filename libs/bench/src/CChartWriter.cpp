#include "roislam/bench/CChartWriter.h"

#include <mrpt/system/string_utils.h>
#include <roislam/bench/CReportWriter.h>
#include <roislam/bench/ProcessUtils.h>
#include <roislam/evaluation/CTrajectoryEvaluator.h>
#include <roislam/io/TumTrajectory.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <iterator>
#include <map>
#include <sstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace roislam::bench
{
namespace
{
const std::vector<std::string> kFeatures{"surf", "sift", "orb"};

std::string shortVersion(const TRunRecord& r)
{
  const auto& m = r.run.mode;
  std::string base = m == "traditional" ? "traditional"
                     : m == "roi_small" ? "small ROI"
                     : m == "roi_big"   ? "big ROI"
                                        : m;
  return r.run.variant.empty() ? base : base + " (" + r.run.variant + ")";
}

std::string gpQuote(const std::string& s)
{
  std::string out = "\"";
  for (char c : s)
  {
    if (c == '"' || c == '\\')
      out += '\\';
    out += c;
  }
  return out + "\"";
}

std::string val(std::optional<double> v)
{
  if (!v || !std::isfinite(*v))
    return "NaN";
  std::ostringstream ss;
  ss.precision(8);
  ss << *v;
  return ss.str();
}

std::string header(const std::string& png, int w, int h, const std::string& title)
{
  return "set terminal pngcairo size " + std::to_string(w) + "," + std::to_string(h) +
         " noenhanced font \"sans,10\"\nset output " + gpQuote(png) + "\nset title " +
         gpQuote(title) + "\nset datafile missing \"NaN\"\nset key outside right top\n";
}

/** Top view: the two axes (in index order) along which the ground truth spreads most. */
std::pair<int, int> topViewAxes(const io::TTrajectory& gt)
{
  std::array<double, 3> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (const auto& p : gt)
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min(lo[a], p.pose.m_coords[a]);
      hi[a] = std::max(hi[a], p.pose.m_coords[a]);
    }
  std::array<int, 3> axes{0, 1, 2};
  std::sort(axes.begin(), axes.end(), [&](int a, int b) { return hi[a] - lo[a] > hi[b] - lo[b]; });
  return {std::min(axes[0], axes[1]), std::max(axes[0], axes[1])};
}
}  // namespace

CChartWriter::CChartWriter() : CChartWriter(TOptions()) {}
CChartWriter::CChartWriter(const TOptions& options) : m_options(options) {}

bool CChartWriter::available() const
{
  if (m_options.gnuplot.find('/') != std::string::npos)
    return fs::exists(m_options.gnuplot);
  return findOnPath(m_options.gnuplot).has_value();
}

void CChartWriter::plot(const std::string& dir, const std::string& name, const std::string& script)
{
  const std::string gp = (fs::path(dir) / (name + ".gp")).string();
  writeFileAtomically(gp, script);
  const std::string err = (fs::path(dir) / (name + ".gnuplot.log")).string();
  fs::remove(err);
  // Scripts use names relative to the chart folder, so gnuplot starts there.
  std::string cdDir;
  for (char c : fs::absolute(dir).string())
    cdDir += (c == '\'' ? std::string("''") : std::string(1, c));
  const auto r = runProcess(
      {m_options.gnuplot, "-e", "cd '" + cdDir + "'", fs::absolute(gp).string()}, "", err, 120);
  const fs::path png = fs::path(dir) / (name + ".png");
  if (!r.succeeded() || !fs::exists(png) || fs::file_size(png) == 0)
    throw std::runtime_error(
        gp + ": gnuplot failed" + (r.error.empty() ? "" : ": " + r.error) + " " + fileTail(err, 3));
}

std::vector<std::string> CChartWriter::write(
    const std::vector<TRunRecord>& records, const std::string& dir)
{
  fs::create_directories(dir);
  m_warnings.clear();
  std::vector<std::string> pngs;
  const auto append = [&](const std::vector<std::string>& more)
  { pngs.insert(pngs.end(), more.begin(), more.end()); };
  append(writeTest1(records, dir));
  for (int test : {2, 3})
    append(writeVersionCharts(records, dir, test));
  append(writeTrajectories(records, dir));
  if (auto png = writeTest4(records, dir))
    pngs.push_back(*png);
  return pngs;
}

std::optional<std::string> CChartWriter::writeTest4(
    const std::vector<TRunRecord>& records, const std::string& dir)
{
  // Clustered bars per sequence and extractor: EKF, odometry, graph SLAM.
  std::vector<std::pair<std::string, std::string>> keys;
  for (const auto& r : records)
    if (r.run.test == 4 &&
        std::find(keys.begin(), keys.end(), std::make_pair(r.run.sequence, r.run.feature)) ==
            keys.end())
      keys.emplace_back(r.run.sequence, r.run.feature);
  if (keys.empty())
    return std::nullopt;
  const auto value = [&](const std::string& s, const std::string& f, const std::string& mode,
                         const std::string& key)
  {
    std::optional<double> v;
    for (const auto& r : records)
      if (r.run.test == 4 && r.run.sequence == s && r.run.feature == f && r.run.mode == mode &&
          r.ok)
        v = r.number(key);
    return v;
  };
  std::ostringstream dat;
  dat << "run \"EKF-SLAM (kf-slam)\" \"odometry alone\" \"graph SLAM\"\n";
  double top = 0;
  for (const auto& [s, f] : keys)
  {
    dat << gpQuote(s + " " + mrpt::system::upperCase(f));
    for (const auto& v :
         {value(s, f, "kf_slam", "kf_slam.ate_rmse"),
          value(s, f, "kf_slam", "kf_slam.odometry_ate_rmse"),
          value(s, f, "graph_slam", "ate_rmse")})
    {
      top = std::max(top, v.value_or(0.0));
      dat << " " << val(v);
    }
    dat << "\n";
  }
  const std::string name = "test4_ate";
  writeFileAtomically((fs::path(dir) / (name + ".dat")).string(), dat.str());
  std::string gp = header(
      name + ".png", m_options.width, m_options.height,
      "Test 4: ATE RMSE (m), EKF-SLAM on ROI landmarks vs odometry alone vs graph SLAM "
      "(missing bar = failed or n/a)");
  gp +=
      "set style data histograms\nset style histogram clustered gap 1\n"
      "set style fill solid 0.8 border -1\nset boxwidth 0.9\n" +
      (top > 0 ? "set yrange [0:" + std::to_string(top * 1.08) + "]\n"
               : std::string("set yrange [0:1]\n")) +
      "set xtics rotate by -20\nset grid ytics\nset ylabel \"ATE RMSE (m)\"\nplot '" + name +
      ".dat' using 2:xtic(1) title columnheader(2), '' using 3 title columnheader(3), "
      "'' using 4 title columnheader(4)\n";
  plot(dir, name, gp);
  return name + ".png";
}

std::vector<std::string> CChartWriter::writeTest1(
    const std::vector<TRunRecord>& records, const std::string& dir)
{
  // Clustered bars per sequence, one bar per extractor.
  std::vector<std::string> pngs;
  const int W = m_options.width, H = m_options.height;
  // One cluster per sequence and variant ("" = plain, e.g. "hue").
  std::vector<std::pair<std::string, std::string>> seqs;
  for (const auto& r : records)
    if (r.run.test == 1)
    {
      const auto key = std::make_pair(r.run.sequence, r.run.variant);
      if (std::find(seqs.begin(), seqs.end(), key) == seqs.end())
        seqs.push_back(key);
    }
  const std::vector<std::pair<std::string, std::string>> t1Metrics{
      {"landmarks", "Test 1: landmarks in the database"},
      {"false_positives", "Test 1: false positives"},
      {"false_negatives", "Test 1: false negatives"}};
  for (const auto& [key, title] : t1Metrics)
  {
    if (seqs.empty())
      break;
    std::ostringstream dat;
    dat << "sequence SURF SIFT ORB\n";
    bool any = false;
    double top = 0;  // headroom above the highest bar
    for (const auto& [s, variant] : seqs)
    {
      dat << gpQuote(variant.empty() ? s : s + " (" + variant + ")");
      for (const auto& f : kFeatures)
      {
        std::optional<double> v;
        for (const auto& r : records)
          if (r.run.test == 1 && r.run.sequence == s && r.run.variant == variant &&
              r.run.feature == f && r.ok)
            v = r.number(key);
        any = any || v.has_value();
        if (v)
          top = std::max(top, *v);
        dat << " " << val(v);
      }
      dat << "\n";
    }
    if (!any)
    {
      m_warnings.push_back("test1_" + key + ": no values (no ground truth?), chart not drawn");
      continue;
    }
    const std::string name = "test1_" + key;
    writeFileAtomically((fs::path(dir) / (name + ".dat")).string(), dat.str());
    std::string gp = header(name + ".png", W, H, title + " (missing bar = failed or n/a)");
    gp +=
        "set style data histograms\nset style histogram clustered gap 1\n"
        "set style fill solid 0.8 border -1\nset boxwidth 0.9\n" +
        (top > 0 ? "set yrange [0:" + std::to_string(top * 1.08) + "]\n"
                 : std::string("set yrange [0:1]\n")) +
        "set xtics rotate by -20\nset grid ytics\n"
        "plot '" +
        name +
        ".dat' using 2:xtic(1) title columnheader(2), '' using 3 title columnheader(3), "
        "'' using 4 title columnheader(4)\n";
    plot(dir, name, gp);
    pngs.push_back(name + ".png");
  }
  return pngs;
}

std::vector<std::string> CChartWriter::writeVersionCharts(
    const std::vector<TRunRecord>& records, const std::string& dir, int test)
{
  // Mean +- std per version, one bar per extractor.
  std::vector<std::pair<std::string, std::string>> versions;  // key, label
  for (const auto& r : records)
    if (r.run.test == test)
    {
      const auto k = r.run.versionKey();
      if (std::none_of(
              versions.begin(), versions.end(), [&](const auto& p) { return p.first == k; }))
        versions.push_back({k, shortVersion(r)});
    }
  if (versions.empty())
    return {};
  std::vector<std::string> feats;
  for (const auto& f : kFeatures)
    if (std::any_of(
            records.begin(), records.end(),
            [&](const TRunRecord& r) { return r.run.test == test && r.run.feature == f; }))
      feats.push_back(f);
  const std::vector<std::array<std::string, 3>> metrics{
      {"ate_rmse", "ATE RMSE (m)", "ate"},
      {"rpe_trans_rmse", "RPE translation RMSE (m)", "rpe_trans"},
      {"rpe_rot_rmse_deg", "RPE rotation RMSE (deg)", "rpe_rot"},
      {"wall_s", "duration per run (s)", "duration"}};
  std::vector<std::string> pngs;
  for (const auto& m : metrics)
    if (auto png = writeVersionChart(records, dir, test, versions, feats, m))
      pngs.push_back(*png);
  return pngs;
}

std::optional<std::string> CChartWriter::writeVersionChart(
    const std::vector<TRunRecord>& records, const std::string& dir, int test,
    const std::vector<std::pair<std::string, std::string>>& versions,
    const std::vector<std::string>& feats, const std::array<std::string, 3>& m)
{
  std::ostringstream dat;
  dat << "# version";
  for (const auto& f : feats)
    dat << " " << mrpt::system::upperCase(f) << " " << mrpt::system::upperCase(f) << "_std";
  dat << "\n";
  bool any = false;
  double top = 0;  // highest mean + std: gnuplot's autoscale ignores error bars
  for (const auto& [key, label] : versions)
  {
    dat << gpQuote(label);
    for (const auto& f : feats)
    {
      std::vector<double> v;
      for (const auto& r : records)
        if (r.run.test == test && r.run.versionKey() == key && r.run.feature == f && r.ok)
        {
          auto x = r.number(m[0]);
          if (!x && m[0] == "wall_s")
            x = r.wallS;
          if (x)
            v.push_back(*x);
        }
      const auto ms = meanStd(v);
      any = any || ms.has_value();
      if (ms)
        top = std::max(top, ms->mean + (std::isfinite(ms->std) ? ms->std : 0.0));
      dat << " " << val(ms ? std::optional<double>(ms->mean) : std::nullopt) << " "
          << val(ms ? std::optional<double>(ms->std) : std::nullopt);
    }
    dat << "\n";
  }
  if (!any)
    return std::nullopt;
  const int W = m_options.width, H = m_options.height;
  const std::string name = "test" + std::to_string(test) + "_" + m[2];
  writeFileAtomically((fs::path(dir) / (name + ".dat")).string(), dat.str());
  std::string gp = header(
      name + ".png", W, H,
      "Test " + std::to_string(test) + ": " + m[1] +
          ", mean +- std over sequences (missing bar = all runs failed)");
  gp +=
      "set style data histograms\nset style histogram errorbars gap 1 lw 1\n"
      "set style fill solid 0.8 border -1\nset boxwidth 0.9\n" +
      (top > 0 ? "set yrange [0:" + std::to_string(top * 1.08) + "]\n"
               : std::string("set yrange [0:*]\n")) +
      "set xtics rotate by -20\nset grid ytics\nset ylabel " + gpQuote(m[1]) + "\nplot ";
  for (std::size_t k = 0; k < feats.size(); ++k)
  {
    gp += (k ? ", '' " : "'" + name + ".dat' ") + std::string("using ") +
          std::to_string(2 + 2 * k) + ":" + std::to_string(3 + 2 * k) + (k == 0 ? ":xtic(1)" : "") +
          " title " + gpQuote(mrpt::system::upperCase(feats[k]));
  }
  gp += "\n";
  plot(dir, name, gp);
  return name + ".png";
}

std::vector<std::string> CChartWriter::writeTrajectories(
    const std::vector<TRunRecord>& records, const std::string& dir)
{
  // Top view per sequence and extractor (Test 2 runs).
  std::map<std::pair<std::string, std::string>, std::vector<const TRunRecord*>> groups;
  std::vector<std::pair<std::string, std::string>> order;
  for (const auto& r : records)
    if (r.run.test == 2)
    {
      const auto k = std::make_pair(r.run.sequence, r.run.feature);
      if (!groups.count(k))
        order.push_back(k);
      groups[k].push_back(&r);
    }
  std::vector<std::string> pngs;
  for (const auto& key : order)
    if (auto png = writeTrajectory(dir, key.first, key.second, groups[key]))
      pngs.push_back(*png);
  return pngs;
}

std::optional<std::string> CChartWriter::writeTrajectory(
    const std::string& dir, const std::string& sequence, const std::string& feature,
    const std::vector<const TRunRecord*>& runs)
{
  const fs::path gtFile = fs::path(runs.front()->run.sequencePath) / "groundtruth.txt";
  if (!fs::exists(gtFile))
    return std::nullopt;
  io::TTrajectory gt;
  try
  {
    gt = io::loadTumTrajectory(gtFile.string());
  }
  catch (const std::exception& e)
  {
    m_warnings.push_back(e.what());
    return std::nullopt;
  }
  if (gt.empty())
    return std::nullopt;
  const auto [ax, ay] = topViewAxes(gt);
  const char* axisName[3] = {"x", "y", "z"};

  const std::string base = "traj_" + sequence + "_" + feature;
  std::string name;
  for (char c : base)
    name += (std::isalnum(static_cast<unsigned char>(c)) || c == '_') ? c : '_';
  std::ostringstream gtDat;
  for (const auto& p : gt)
    gtDat << p.pose.m_coords[ax] << " " << p.pose.m_coords[ay] << "\n";
  writeFileAtomically((fs::path(dir) / (name + "_gt.dat")).string(), gtDat.str());
  std::string plots = "'" + name + "_gt.dat' using 1:2 with lines lw 2 lc rgb \"black\" title " +
                      gpQuote("ground truth");
  int idx = 0;
  for (const auto* r : runs)
    plots += trajectoryPlot(dir, name, ++idx, *r, gt, ax, ay);
  std::string gp = header(
      name + ".png", m_options.width, m_options.height,
      "Top view, " + sequence + ", " + mrpt::system::upperCase(feature) +
          " (estimates aligned to the ground truth as for the ATE)");
  gp += "set key below\nset size ratio -1\nset grid\nset xlabel " +
        gpQuote(std::string(axisName[ax]) + " (m)") + "\nset ylabel " +
        gpQuote(std::string(axisName[ay]) + " (m)") + "\nplot " + plots + "\n";
  plot(dir, name, gp);
  return name + ".png";
}

std::string CChartWriter::trajectoryPlot(
    const std::string& dir, const std::string& name, int idx, const TRunRecord& r,
    const io::TTrajectory& gt, int ax, int ay)
{
  // Distinct, colour-blind-safe colours; black is the ground truth's.
  static const char* const kColours[] = {"#E69F00", "#56B4E9", "#009E73", "#D55E00",
                                         "#0072B2", "#CC79A7", "#8C564B", "#7F7F7F"};
  const std::string colour =
      std::string("lc rgb \"") + kColours[(idx - 1) % std::size(kColours)] + "\" ";
  std::string label = shortVersion(r);
  const fs::path est = fs::path(r.run.appOutputDir) / "trajectory.txt";
  if (!r.ok || !fs::exists(est))
    return ", NaN with lines " + colour + "title " + gpQuote(label + ": failed");
  try
  {
    const auto res =
        evaluation::CTrajectoryEvaluator().evaluate(gt, io::loadTumTrajectory(est.string()));
    std::ostringstream d;
    for (const auto& p : res.aligned)
      d << p.pose.m_coords[ax] << " " << p.pose.m_coords[ay] << "\n";
    const std::string f = name + "_" + std::to_string(idx) + ".dat";
    writeFileAtomically((fs::path(dir) / f).string(), d.str());
    std::ostringstream ate;
    ate.precision(3);
    ate << res.ate.rmse;
    return ", '" + f + "' using 1:2 with lines lw 1.5 " + colour +
           (r.run.variant == "strict" ? "dt 2 " : "") + "title " +
           gpQuote(label + ", ATE " + ate.str() + " m");
  }
  catch (const std::exception& e)
  {
    m_warnings.push_back(est.string() + ": not plotted: " + e.what());
    return ", NaN with lines " + colour + "title " + gpQuote(label + ": not aligned");
  }
}
}  // namespace roislam::bench
