#include "roislam/bench/CResultsCollector.h"

#include <roislam/bench/CBenchRunner.h>
#include <roislam/bench/ProcessUtils.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace roislam::bench
{
namespace
{
std::string csvField(const std::string& s)
{
  if (s.find_first_of(",\"\n\r") == std::string::npos)
    return s;
  std::string out = "\"";
  for (char c : s)
  {
    if (c == '"')
      out += '"';
    out += c;
  }
  return out + "\"";
}

std::string jsonScalar(const nlohmann::json& v)
{
  if (v.is_null())
    return "";
  if (v.is_string())
    return v.get<std::string>();
  if (v.is_boolean())
    return v.get<bool>() ? "true" : "false";
  if (v.is_number_integer())
    return std::to_string(v.get<long long>());
  if (v.is_number())
  {
    std::ostringstream ss;
    ss.precision(10);
    ss << v.get<double>();
    return ss.str();
  }
  return v.dump();
}

std::string fmt(double v)
{
  std::ostringstream ss;
  ss.precision(6);
  ss << v;
  return ss.str();
}
}  // namespace

std::vector<TRunRecord> CResultsCollector::loadFolder(const std::string& outputDir)
{
  std::vector<TRunRecord> out;
  const fs::path runs = fs::path(outputDir) / "runs";
  if (!fs::is_directory(runs))
    return out;
  std::vector<fs::path> dirs;
  for (const auto& e : fs::directory_iterator(runs))
    if (e.is_directory())
      dirs.push_back(e.path());
  std::sort(dirs.begin(), dirs.end());
  for (const auto& d : dirs)
    if (auto rec = CBenchRunner::loadCompleted(d.string()))
      out.push_back(*rec);
  return out;
}

std::vector<TRunRecord> CResultsCollector::merge(
    const std::vector<std::string>& sources, const std::string& dest)
{
  const fs::path destRuns = fs::path(dest) / "runs";
  fs::create_directories(destRuns);
  for (const auto& src : sources)
  {
    if (!fs::is_directory(fs::path(src) / "runs"))
      throw std::runtime_error(src + ": not a roi-bench output folder (no runs/ inside)");
    if (fs::equivalent(fs::path(src), fs::path(dest)))
      continue;
    for (const auto& rec : loadFolder(src))
    {
      const fs::path target = destRuns / rec.run.id;
      const auto existing = CBenchRunner::loadCompleted(target.string());
      if (existing && (existing->ok || !rec.ok))
        continue;
      // Copy to a temporary name first so an interrupted merge leaves no half folder.
      const fs::path tmp = destRuns / (".merge-" + rec.run.id);
      fs::remove_all(tmp);
      fs::copy(rec.run.runDir, tmp, fs::copy_options::recursive);
      fs::remove_all(target);
      fs::rename(tmp, target);
    }
  }
  return loadFolder(dest);
}

std::vector<TRunRecord> CResultsCollector::orderByPlan(
    const std::vector<TRunRecord>& records, const std::vector<TBenchRun>& plan)
{
  std::map<std::string, const TRunRecord*> byId;
  for (const auto& r : records)
    byId[r.run.id] = &r;
  std::vector<TRunRecord> out;
  std::set<std::string> used;
  for (const auto& p : plan)
  {
    const auto it = byId.find(p.id);
    if (it == byId.end())
      continue;
    out.push_back(*it->second);
    used.insert(p.id);
  }
  for (const auto& r : records)
    if (!used.count(r.run.id))
      out.push_back(r);
  return out;
}

namespace
{
// ------------------------------------------------------------- toCsv stages

/** Known summary fields (both apps' contracts), in column order. */
std::vector<std::string> knownSummaryKeys()
{
  return {
      "frames",
      "frames_with_roi",
      "landmarks",
      "recalls",
      "false_positives",
      "false_negatives",
      "precision",
      "recall",
      "matches_per_frame",
      "false_matches_per_frame",
      "duration_s",
      "keyframes",
      "loop_closures",
      "tracked_frames",
      "fallback_frames",
      "lost_frames",
      "wall_s",
      "fps",
      "ms_per_frame",
      "failed_frames",
      "peak_rss_mb",
      "ate_rmse",
      "rpe_trans_rmse",
      "rpe_rot_rmse_deg",
      "failed"};
}

/** Adds the scalar leaves under `v` as "prefix.key..." columns (arrays are
 *  left out: a column holds one value). */
void addLeaves(const std::string& prefix, const nlohmann::json& v, std::set<std::string>& out)
{
  for (const auto& [k, child] : v.items())
    if (child.is_object())
      addLeaves(prefix + k + ".", child, out);
    else if (!child.is_array())
      out.insert(prefix + k);
}

/** Summary fields seen in the records beyond the known ones, sorted. */
std::set<std::string> extraSummaryKeys(
    const std::vector<TRunRecord>& records, const std::set<std::string>& known)
{
  std::set<std::string> extra;
  // Objects at any depth (roi-landmarks' "kf_slam", roi-graphslam's
  // "edge_chi2.with_ground_truth_noise") become "object.key" columns.
  for (const auto& r : records)
    if (r.summary.is_object())
      for (const auto& [k, v] : r.summary.items())
      {
        if (v.is_object())
          addLeaves(k + ".", v, extra);
        else if (!known.count(k) && !v.is_array())
          extra.insert(k);
      }
  return extra;
}

void writeCsvHeader(std::ostream& out, const std::vector<std::string>& keys)
{
  out << "run_id,test,sequence,app,mode,feature,max_features,variant,status,failure_reason,"
         "exit_code,signal,bench_wall_s,bench_cpu_s,bench_max_rss_mb,started_utc,host";
  for (const auto& k : keys)
    out << "," << k;
  out << ",command\n";
}

void writeCsvRow(std::ostream& out, const TRunRecord& r, const std::vector<std::string>& keys)
{
  out << csvField(r.run.id) << "," << r.run.test << "," << csvField(r.run.sequence) << ","
      << r.run.app << "," << r.run.mode << "," << r.run.feature << "," << r.run.maxFeatures << ","
      << csvField(r.run.variant) << "," << (r.ok ? "ok" : "failed") << ","
      << csvField(r.failureReason) << "," << r.exitCode << "," << r.signal << "," << fmt(r.wallS)
      << "," << fmt(r.cpuS) << "," << fmt(r.maxRssMb) << "," << r.startedUtc << ","
      << csvField(r.host);
  for (const auto& k : keys)
  {
    out << ",";
    if (const auto* v = r.field(k))
      out << csvField(jsonScalar(*v));
  }
  out << "," << csvField(shellJoin(r.run.argv)) << "\n";
}
}  // namespace

std::string CResultsCollector::toCsv(const std::vector<TRunRecord>& records)
{
  // Known summary fields first (both apps' contracts), then anything else seen.
  std::vector<std::string> keys = knownSummaryKeys();
  const std::set<std::string> known(keys.begin(), keys.end());
  const std::set<std::string> extra = extraSummaryKeys(records, known);
  keys.insert(keys.end(), extra.begin(), extra.end());

  std::ostringstream out;
  writeCsvHeader(out, keys);
  for (const auto& r : records)
    writeCsvRow(out, r, keys);
  return out.str();
}

void CResultsCollector::writeCsv(const std::vector<TRunRecord>& records, const std::string& file)
{
  writeFileAtomically(file, toCsv(records));
}
}  // namespace roislam::bench
