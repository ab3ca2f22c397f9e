#include "roislam/bench/CBenchApp.h"

#include <roislam/bench/CChartWriter.h>
#include <roislam/bench/CDissertationReference.h>
#include <roislam/bench/CPairedSlamCost.h>
#include <roislam/bench/CProgressBar.h>
#include <roislam/bench/CReportWriter.h>
#include <roislam/bench/CResultsCollector.h>
#include <roislam/bench/ProcessUtils.h>
#include <roislam/common/COutputFolder.h>
#include <roislam/common/CStrictIniFile.h>
#include <roislam/common/IniKeyCheck.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <stdexcept>

#ifndef ROISLAM_BENCH_SOURCE_DIR
#define ROISLAM_BENCH_SOURCE_DIR ""
#endif

namespace fs = std::filesystem;

namespace roislam::bench
{
namespace
{
bool isExecutable(const fs::path& p)
{
  return fs::is_regular_file(p) && access(p.c_str(), X_OK) == 0;
}

/** roi-bench's output folder may be reused (resumed), but only as ours. */
void checkBenchFolder(const std::string& dir)
{
  common::COutputFolder::TOptions o;
  o.overwrite = true;
  o.known = {"runs", "configs", "results.csv", "report.md", "charts", "speed.json"};
  // Temporary names of results.csv / report.md / speed.json being written.
  o.knownPrefixes = {"results.csv.", "report.md.", "speed.json."};
  common::COutputFolder::checkReplaceable(dir, o);
}
}  // namespace

CBenchApp::CBenchApp(const TOptions& options) : m_options(options)
{
  if (m_options.outputDir.empty())
    throw std::invalid_argument("--output-dir is required");
  if (m_options.jobs < 1)
    throw std::invalid_argument("--jobs must be >= 1");
  if (m_options.speedPasses < 0)
    throw std::invalid_argument("--speed-passes must be >= 0");
  if (m_options.selfExe.empty())
    m_options.selfExe = selfExecutablePath();
  // A bare --merge (re-make the report of --output-dir) may arrive as one empty value.
  auto& md = m_options.mergeDirs;
  md.erase(std::remove(md.begin(), md.end(), std::string()), md.end());
  if (!m_options.planFile.empty())
  {
    const common::CStrictIniFile cfg(m_options.planFile);
    common::checkIniKeys(cfg, "Bench", common::knownIniKeys(m_options.plan), m_options.planFile);
    m_options.plan.loadFromConfigFile(cfg, "Bench");
  }
  if (!m_options.tests.empty())
    m_options.plan.tests = CExperimentPlan::parseTests(m_options.tests);
  if (m_options.noDefaultVariants)
  {
    m_options.plan.variants.clear();
    m_options.plan.test1_variants.clear();
  }
  for (const auto& spec : m_options.variantSpecs)
    m_options.plan.variants.push_back(TVariant::parse(spec));
  m_options.plan.reference_methods =
      CExperimentPlan::parseReferenceMethods(m_options.referenceMethods);
  m_options.plan.validate();
  if (!m_options.merge && m_options.datasets.empty())
    throw std::invalid_argument("--datasets is required (unless --merge)");
}

std::string CBenchApp::executableFor(const std::string& app) const
{
  if (!m_options.binDir.empty())
  {
    for (const auto& p : {fs::path(m_options.binDir) / app, fs::path(m_options.binDir) / app / app})
      if (isExecutable(p))
        return fs::absolute(p).string();
    throw std::runtime_error("--bin-dir " + m_options.binDir + ": no executable " + app);
  }
  if (!m_options.selfExe.empty())
  {
    const fs::path self = fs::path(m_options.selfExe).parent_path();
    for (const auto& p : {self.parent_path() / app / app, self / app})
      if (isExecutable(p))
        return p.string();
  }
  if (auto p = findOnPath(app))
    return *p;
  return app;  // reported as a failed run ("cannot start") if it is really missing
}

std::string CBenchApp::configDir() const
{
  if (!m_options.configDir.empty())
    return fs::absolute(m_options.configDir).string();
  const fs::path src = fs::path(ROISLAM_BENCH_SOURCE_DIR) / "config";
  if (!std::string(ROISLAM_BENCH_SOURCE_DIR).empty() && fs::is_directory(src))
    return src.string();
  const fs::path inst =
      fs::path(m_options.selfExe).parent_path().parent_path() / "share" / "roislam" / "config";
  if (fs::is_directory(inst))
    return inst.string();
  throw std::runtime_error("no config folder found: pass --config-dir");
}

std::string CBenchApp::referenceFile() const
{
  if (!m_options.reference.empty())
    return m_options.reference;
  const fs::path src =
      fs::path(ROISLAM_BENCH_SOURCE_DIR) / "share" / "roi-bench" / "dissertation.json";
  if (!std::string(ROISLAM_BENCH_SOURCE_DIR).empty() && fs::exists(src))
    return src.string();
  const fs::path inst = fs::path(m_options.selfExe).parent_path().parent_path() / "share" /
                        "roislam" / "roi-bench" / "dissertation.json";
  return fs::exists(inst) ? inst.string() : std::string();
}

std::vector<TBenchRun> CBenchApp::plan() const
{
  CExperimentPlan::TLocations loc;
  for (const auto& app : {"roi-landmarks", "roi-graphslam", "cv-odometry"})
    loc.executables[app] = executableFor(app);
  loc.configDir = configDir();
  loc.outputDir = fs::absolute(m_options.outputDir).lexically_normal().string();
  auto runs = CExperimentPlan(m_options.plan, loc)
                  .build(CExperimentPlan::discoverSequences(m_options.datasets));
  if (m_options.only.empty())
    return runs;
  std::set<std::string> wanted(m_options.only.begin(), m_options.only.end());
  std::vector<TBenchRun> out;
  for (auto& r : runs)
    if (wanted.erase(r.id))
      out.push_back(r);
  if (!wanted.empty())
    throw std::invalid_argument("--only: no planned run " + *wanted.begin());
  return out;
}

std::vector<std::string> CBenchApp::jobCommands() const
{
  std::vector<std::string> base{
      m_options.selfExe.empty() ? "roi-bench" : m_options.selfExe, "--datasets"};
  for (const auto& d : m_options.datasets)
    base.push_back(fs::absolute(d).string());
  // The tests in effect (from --tests or the plan file).
  std::string tests;
  for (int t : m_options.plan.tests)
    tests += (tests.empty() ? "" : ",") + std::to_string(t);
  base.insert(
      base.end(), {"--output-dir", fs::absolute(m_options.outputDir).string(), "--tests", tests,
                   "--jobs", "1", "--no-report"});
  if (!m_options.planFile.empty())
    base.insert(base.end(), {"--plan", fs::absolute(m_options.planFile).string()});
  if (!m_options.binDir.empty())
    base.insert(base.end(), {"--bin-dir", fs::absolute(m_options.binDir).string()});
  if (!m_options.configDir.empty())
    base.insert(base.end(), {"--config-dir", fs::absolute(m_options.configDir).string()});
  if (m_options.timeoutS > 0)
    base.insert(base.end(), {"--timeout", std::to_string(m_options.timeoutS)});
  if (m_options.retryFailed)
    base.push_back("--retry-failed");
  if (m_options.noDefaultVariants)
    base.push_back("--no-default-variants");
  for (const auto& v : m_options.variantSpecs)
    base.insert(base.end(), {"--variant", v});
  base.insert(base.end(), {"--reference-methods", m_options.referenceMethods});
  std::vector<std::string> out;
  for (const auto& r : plan())
  {
    auto argv = base;
    argv.insert(argv.end(), {"--only", r.id});
    out.push_back(shellJoin(argv));
  }
  return out;
}

void CBenchApp::writeOutputs(const std::vector<TRunRecord>& records, std::ostream& err) const
{
  const fs::path out(m_options.outputDir);
  fs::create_directories(out);
  CResultsCollector::writeCsv(records, (out / "results.csv").string());
  CReportWriter::TOptions ro;
  ro.jobs = m_options.jobs;
  if (fs::exists(out / "speed.json"))
    ro.pairedCostFile = (out / "speed.json").string();
  if (m_options.charts)
  {
    CChartWriter charts;
    if (!charts.available())
      err << "roi-bench: warning: gnuplot not found, no charts drawn\n";
    else
    {
      // Replaced whole: no chart of an earlier report survives.
      common::COutputFolder::TOptions chartsFolder;
      chartsFolder.overwrite = chartsFolder.ownsEverything = true;
      common::COutputFolder dir((out / "charts").string(), chartsFolder);
      for (const auto& png : charts.write(records, dir.path()))
        ro.charts.push_back("charts/" + png);
      dir.commit();
      for (const auto& w : charts.warnings())
        err << "roi-bench: warning: " << w << "\n";
    }
  }
  const std::string refFile = referenceFile();
  CDissertationReference ref;
  if (refFile.empty())
    err << "roi-bench: warning: dissertation.json not found, report without reference values\n";
  else
    ref = CDissertationReference::fromFile(refFile);
  CReportWriter(ro, ref).write(records, (out / "report.md").string());
}

namespace
{
/** Test-2 records grouped by sequence x extractor, in plan order. */
std::vector<std::vector<const TRunRecord*>> test2Groups(const std::vector<TRunRecord>& records)
{
  std::vector<std::vector<const TRunRecord*>> groups;
  for (const auto& r : records)
  {
    if (r.run.test != 2)
      continue;
    auto g = std::find_if(
        groups.begin(), groups.end(),
        [&](const auto& grp)
        {
          return grp.front()->run.sequence == r.run.sequence &&
                 grp.front()->run.feature == r.run.feature;
        });
    if (g == groups.end())
      groups.push_back({&r});
    else
      g->push_back(&r);
  }
  return groups;
}

/** One group's measurement as planned: its speed.json entry (the versions
 *  to measure, those left out and why, or the error when there is nothing
 *  to compare) and the options that measure it. */
struct TPairedCostPlan
{
  TPairedCost entry;
  CPairedSlamCost::TOptions options;
};

/** The versions of one sequence x extractor to measure, traditional first
 *  (the ratios' reference), `passes` passes. */
TPairedCostPlan planGroup(const std::vector<const TRunRecord*>& group, int passes)
{
  const TRunRecord& first = *group.front();
  TPairedCostPlan plan;
  TPairedCost& planned = plan.entry;
  planned.sequence = first.run.sequence;
  planned.sequencePath = first.run.sequencePath;
  planned.feature = first.run.feature;
  planned.maxFeatures = first.run.maxFeatures;
  planned.passes = passes;
  std::vector<const TRunRecord*> ordered;
  for (const auto* r : group)
    if (r->run.mode == "traditional")
      ordered.insert(ordered.begin(), r);
    else
      ordered.push_back(r);
  CPairedSlamCost::TOptions& o = plan.options;
  o.sequence = planned.sequencePath;
  o.max_features = planned.maxFeatures > 0 ? planned.maxFeatures : -1;
  o.passes = planned.passes;
  for (const auto* r : ordered)
  {
    // A version that could not run the whole sequence alone (the strict
    // ROI when it loses frames) has no cost to compare.
    if (!r->ok)
    {
      planned.leftOut.emplace_back(
          r->run.versionKey(), "its Test-2 run failed: " + r->failureReason);
      continue;
    }
    CPairedSlamCost::TVersion v;
    v.key = r->run.versionKey();
    v.label = CReportWriter::versionLabel(*r);
    v.iniFile = r->run.baseIni;
    v.overrides = r->run.iniOverrides;
    // As the app's --mode, which overrides the ini's.
    v.overrides.push_back({"FrontEnd", "mode", r->run.mode});
    o.versions.push_back(v);
    TPairedCost::TVersion pv;
    pv.key = v.key;
    pv.iniFile = v.iniFile;
    planned.versions.push_back(pv);
  }
  if (ordered.front()->run.mode != "traditional" || !ordered.front()->ok)
  {
    planned.versions.clear();
    planned.error = "no successful traditional Test-2 run to compare with";
  }
  else if (planned.versions.size() < 2)
  {
    planned.versions.clear();
    planned.error = "no ROI version to compare with traditional";
  }
  return plan;
}

/** The measurement CBenchApp would make now for an entry, to compare with one
 *  found in speed.json. */
bool sameMeasurement(const TPairedCost& a, const TPairedCost& b)
{
  if (a.sequencePath != b.sequencePath || a.feature != b.feature ||
      a.maxFeatures != b.maxFeatures || a.passes != b.passes || a.maxFrames != b.maxFrames ||
      a.versions.size() != b.versions.size())
    return false;
  for (std::size_t k = 0; k < a.versions.size(); ++k)
    if (a.versions[k].key != b.versions[k].key || a.versions[k].iniFile != b.versions[k].iniFile)
      return false;
  return true;
}

/** The speed.json entry of a planned group: the one in `previous` for the
 *  same versions and passes when there is one (a failed one too, unless
 *  retryFailed), else measured now; a failed measurement keeps its versions
 *  (without figures) to tell what was tried. Progress and warnings to err. */
TPairedCost measureOrKeep(
    TPairedCostPlan plan, const std::vector<TPairedCost>& previous, bool retryFailed,
    std::ostream& err)
{
  TPairedCost& planned = plan.entry;
  CPairedSlamCost::TOptions& o = plan.options;
  const auto kept = std::find_if(
      previous.begin(), previous.end(),
      [&](const TPairedCost& p)
      {
        return planned.error.empty() && p.sequence == planned.sequence &&
               sameMeasurement(p, planned) && (p.ok() || !retryFailed);
      });
  if (kept != previous.end())
    return *kept;
  const std::string what = planned.sequence + ", " + planned.feature;
  if (planned.error.empty())
  {
    err << "roi-bench: paired speed measurement " << what << ": " << o.versions.size()
        << " versions, " << o.passes << " pass(es)\n";
    try
    {
      o.feature = features::featureTypeFromString(planned.feature);
      const TPairedCost measured = CPairedSlamCost(o).run();
      planned.versions = measured.versions;
    }
    catch (const std::exception& e)
    {
      planned.error = e.what();
    }
  }
  if (!planned.error.empty())
    err << "roi-bench: warning: paired speed measurement " << what << ": " << planned.error << "\n";
  return planned;
}
}  // namespace

void CBenchApp::measurePairedCosts(const std::vector<TRunRecord>& records, std::ostream& err) const
{
  const auto groups = test2Groups(records);
  if (groups.empty())
    return;
  const std::string file = (fs::path(m_options.outputDir) / "speed.json").string();
  std::vector<TPairedCost> previous;
  if (fs::exists(file))
    previous = loadPairedCosts(file);
  std::vector<TPairedCost> costs;
  for (const auto& group : groups)
  {
    costs.push_back(measureOrKeep(
        planGroup(group, m_options.speedPasses), previous, m_options.retryFailed, err));
    // Entry by entry: an interrupted stage keeps what it measured.
    savePairedCosts(costs, file);
  }
}

void CBenchApp::mergePairedCosts() const
{
  std::vector<TPairedCost> costs;
  bool any = false;
  for (const auto& dir : m_options.mergeDirs)
  {
    const fs::path f = fs::path(dir) / "speed.json";
    if (!fs::exists(f))
      continue;
    any = true;
    for (auto& c : loadPairedCosts(f.string()))
    {
      // A later folder's entry for the same sequence and extractor wins.
      const auto same = std::find_if(
          costs.begin(), costs.end(),
          [&](const TPairedCost& p) { return p.sequence == c.sequence && p.feature == c.feature; });
      if (same != costs.end())
        *same = std::move(c);
      else
        costs.push_back(std::move(c));
    }
  }
  // Without any, the output's own speed.json (if any) stays.
  if (any)
    savePairedCosts(costs, (fs::path(m_options.outputDir) / "speed.json").string());
}

int CBenchApp::run(std::ostream& out, std::ostream& err)
{
  if (m_options.merge)
  {
    checkBenchFolder(m_options.outputDir);
    auto records = CResultsCollector::merge(m_options.mergeDirs, m_options.outputDir);
    mergePairedCosts();
    if (!m_options.datasets.empty())
      records = CResultsCollector::orderByPlan(records, plan());
    writeOutputs(records, err);
    out << "merged " << records.size() << " runs into " << m_options.outputDir << "\n";
    return 0;
  }
  if (m_options.emitJobs)
  {
    for (const auto& c : jobCommands())
      out << c << "\n";
    return 0;
  }
  checkBenchFolder(m_options.outputDir);
  const auto runs = plan();
  CExperimentPlan::writeVariantConfigs(runs);
  CBenchRunner::TOptions rOpt;
  rOpt.jobs = m_options.jobs;
  rOpt.timeout_s = m_options.timeoutS;
  rOpt.retry_failed = m_options.retryFailed;
  CProgressBar bar(err);
  const auto records =
      CBenchRunner(rOpt).run(runs, [&](const CBenchRunner::TProgress& p) { bar.update(p); });
  std::size_t failed = 0;
  for (const auto& r : records)
    failed += r.ok ? 0 : 1;
  // Only a whole plan has every version of a sequence to pair.
  if (m_options.speedPasses > 0 && m_options.only.empty())
    measurePairedCosts(records, err);
  if (!m_options.noReport)
    writeOutputs(records, err);
  out << records.size() << " runs, " << failed << " failed; results in " << m_options.outputDir
      << "\n";
  return 0;
}
}  // namespace roislam::bench
