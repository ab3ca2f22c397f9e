#include "roislam/bench/CPairedSlamCost.h"

#include <roislam/bench/CostTiming.h>
#include <roislam/common/CStrictIniFile.h>
#include <roislam/common/TextFiles.h>
#include <roislam/evaluation/CTrajectoryEvaluator.h>
#include <roislam/graphslam/CSlamContext.h>
#include <roislam/graphslam/CSlamPipeline.h>
#include <roislam/graphslam/SensorFacts.h>
#include <roislam/io/CFrameSource.h>
#include <roislam/io/TumTrajectory.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <memory>
#include <stdexcept>

namespace fs = std::filesystem;

namespace roislam::bench
{
namespace
{
/** A version's config as roi-graphslam would load it from the derived ini. */
struct TLoadedVersion
{
  graphslam::CSlamContext::TConfig config;
  bool iniReadout = false;  //!< the ini sets rolling_shutter_ms itself
};

TLoadedVersion loadVersion(const CPairedSlamCost::TVersion& v, const CPairedSlamCost::TOptions& o)
{
  if (!fs::is_regular_file(v.iniFile))
    throw std::runtime_error("ini " + v.iniFile + ": no such file");
  // Strictly, as the app reads its --ini; errors name the base file (the
  // overrides only replace values of existing lines or append lines).
  const auto cfg = common::CStrictIniFile::fromText(
      applyIniOverrides(common::readFile(v.iniFile), v.overrides), v.iniFile);
  TLoadedVersion out;
  out.config = graphslam::CSlamContext::loadConfig(cfg, v.iniFile);
  out.iniReadout = graphslam::iniSetsReadout(cfg, v.iniFile);
  out.config.frontEnd.extractor.feature_type = o.feature;
  if (o.max_features >= 0)
    out.config.frontEnd.extractor.max_features = o.max_features;
  return out;
}

/** Sums over the passes of one version. */
struct TSums
{
  double wallMs = 0, cpuMs = 0, frontMs = 0;
  std::size_t frames = 0, lastFrames = 0, lastLost = 0;
  std::optional<double> ate;
};

/** Adds a finished pass of one version to its sums: frames, lost frames,
 *  front-end time, and the ATE of this pass. */
void addPass(const graphslam::CSlamPipeline& p, TSums& s)
{
  const auto& records = p.records();
  s.frames += records.size();
  s.lastFrames = records.size();
  s.lastLost = static_cast<std::size_t>(
      std::count_if(records.begin(), records.end(), [](const auto& r) { return !r.result.pose; }));
  // The front end's own time (frames.csv frontend_ms: decode excluded).
  for (const auto& r : records)
    s.frontMs += r.result.times.total_ms;
  // Same figure as roi-graphslam's: the runs are the app's runs.
  s.ate.reset();
  const auto gt = p.source().groundTruthFile();
  if (gt && fs::exists(*gt))
  {
    try
    {
      s.ate = evaluation::CTrajectoryEvaluator()
                  .evaluate(io::loadTumTrajectory(*gt), p.trajectory())
                  .ate.rmse;
    }
    catch (const std::exception&)
    {
      // Too short for the evaluation: no figure.
    }
  }
}

/** The measurement's result from the versions' sums: per-frame figures
 *  and ratios to the first version. */
TPairedCost summarize(const CPairedSlamCost::TOptions& o, const std::vector<TSums>& sums)
{
  const auto& versions = o.versions;
  TPairedCost out;
  out.sequencePath = o.sequence;
  out.feature = features::toString(o.feature);
  out.maxFeatures = o.max_features;
  out.passes = o.passes;
  out.maxFrames = o.max_frames;
  const auto ratio = [](double a, double b) { return b > 0 ? a / b : 0.0; };
  for (std::size_t m = 0; m < sums.size(); ++m)
  {
    const TSums& s = sums[m];
    const double frames = static_cast<double>(std::max<std::size_t>(s.frames, 1));
    TPairedCost::TVersion v;
    v.key = versions[m].key;
    v.label = versions[m].label;
    v.iniFile = versions[m].iniFile;
    v.overrides = versions[m].overrides;
    v.frames = s.lastFrames;
    v.lostFrames = s.lastLost;
    v.wallMsPerFrame = s.wallMs / frames;
    v.cpuMsPerFrame = s.cpuMs / frames;
    v.frontEndMsPerFrame = s.frontMs / frames;
    v.fps = s.wallMs > 0 ? 1e3 * frames / s.wallMs : 0;
    v.ateRmse = s.ate;
    v.wallRatio = ratio(s.wallMs, sums[0].wallMs);
    v.cpuRatio = ratio(s.cpuMs, sums[0].cpuMs);
    v.frontEndRatio = ratio(s.frontMs, sums[0].frontMs);
    out.versions.push_back(std::move(v));
  }
  return out;
}
}  // namespace

CPairedSlamCost::CPairedSlamCost(TOptions options) : m_options(std::move(options))
{
  if (m_options.versions.empty())
    throw std::invalid_argument("paired cost: no version to measure");
  if (m_options.passes < 1)
    throw std::invalid_argument("paired cost: passes must be >= 1");
  // Every config is checked now, so a bad ini fails before any frame runs.
  for (const auto& v : m_options.versions)
    loadVersion(v, m_options);
}

TPairedCost CPairedSlamCost::run() const
{
  const auto& versions = m_options.versions;
  const std::size_t n = versions.size();
  std::vector<TSums> sums(n);
  for (int pass = 0; pass < m_options.passes; ++pass)
  {
    std::vector<std::unique_ptr<graphslam::CSlamPipeline>> pipe(n);
    for (std::size_t m = 0; m < n; ++m)
    {
      auto loaded = loadVersion(versions[m], m_options);
      auto source = io::CFrameSource::open(m_options.sequence);
      graphslam::applySensorFacts(
          loaded.config.frontEnd, source->sensor(), loaded.iniReadout, "", versions[m].iniFile, {});
      pipe[m] = std::make_unique<graphslam::CSlamPipeline>(loaded.config, std::move(source));
      pipe[m]->waitForPrefetch();
    }
    const auto guarded = [&](std::size_t m, auto&& f)
    {
      try
      {
        f();
      }
      catch (const std::exception& e)
      {
        throw std::runtime_error(versions[m].key + ": " + e.what());
      }
    };
    bool more = true;
    const std::size_t limit = m_options.max_frames;
    for (std::size_t k = 0; more && (limit == 0 || k < limit); ++k)
      for (std::size_t j = 0; j < n; ++j)
      {
        const std::size_t m = (j + k) % n;
        guarded(
            m,
            [&]
            {
              timed(
                  [&]
                  {
                    more = pipe[m]->step() && more;
                    pipe[m]->waitForPrefetch();
                  },
                  sums[m].wallMs, sums[m].cpuMs);
            });
      }
    for (std::size_t m = 0; m < n; ++m)
    {
      guarded(m, [&] { timed([&] { pipe[m]->finish(); }, sums[m].wallMs, sums[m].cpuMs); });
      addPass(*pipe[m], sums[m]);
    }
  }

  return summarize(m_options, sums);
}
}  // namespace roislam::bench
