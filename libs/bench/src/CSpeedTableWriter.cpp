#include "CSpeedTableWriter.h"

#include <mrpt/system/string_utils.h>
#include <roislam/bench/CReportWriter.h>

#include <algorithm>
#include <utility>

#include "ReportTables.h"

namespace roislam::bench
{
using namespace report;

namespace
{
/** The paired table's heading, what its figures are, and its header. */
void pairedIntroduction(std::ostream& md, int passes)
{
  md << "## Speed (Test 2 versions, paired measurement)\n\n"
        "Figures from `speed.json`, not from the Test-2 runs: per sequence and extractor, "
        "roi-bench ran traditional and every Test-2 ROI version again in one process, each "
        "as roi-graphslam runs it (CSlamPipeline: decoding and the ROI one frame ahead, front "
        "end, back end, final optimisation; the run's ini, variant overrides and feature cap), "
        "stepped in turn frame by frame with the order rotated, so load on the machine hits "
        "every version alike ("
     << passes
     << " pass(es); bench::CPairedSlamCost, the measurement of `roislam-stage-bench "
        "--paired-slam-passes`). A version whose Test-2 run failed on a sequence (the strict "
        "ROI when it loses frames) is left out of that sequence's measurement.\n\n"
        "front end = the front end's own time per frame, decoding excluded (frames.csv "
        "frontend_ms), mean over the sequences; front-end ratio = its sum over the sequences "
        "over traditional's on the same sequences; fps = frames / wall time of the version's "
        "steps (waiting for its next frame included) and final optimisation, mean over the "
        "sequences; cost ratio = the same ratio for that wall time (< 1: cheaper than "
        "traditional); CPU cost ratio = the same for process CPU time. Peak RSS = largest "
        "peak RSS of the version's Test-2 runs (each alone in its process).\n\n"
        "| version | extractor | front end (ms/frame) | front-end ratio vs traditional | fps "
        "| cost ratio vs traditional | CPU cost ratio | peak RSS (MiB) "
        "|\n|---|---|---|---|---|---|---|---|\n";
}

/** The single runs' table's heading, what its figures are, and its header. */
void unpairedIntroduction(std::ostream& md)
{
  md << "## Speed (Test 2 runs, measured in this benchmark)\n\n"
        "No paired measurement in this folder (roi-bench --speed-passes 0, or runs merged "
        "without one): every figure below is from the Test-2 runs themselves.\n\n"
        "fps = frames / wall time of the app (summary.json); ratio = sum of this version's "
        "wall time over the sum of the traditional version's, on the sequences where both "
        "succeeded; peak memory = largest peak RSS (app's figure, else wait4's). Each figure "
        "comes from one run: on a shared machine single runs vary by 10-20 %, so ratios "
        "within that band are not differences; `roislam-stage-bench --paired-passes 2 "
        "--benchmark_filter=FrontEnd` interleaves the versions frame by frame for a robust "
        "ratio.\n\n"
        "front end = all front-end work per frame, decoding excluded (summary.json "
        "frontend_ms_per_frame, mean over the sequences), and its ratio to the traditional "
        "version's on the same sequences. The paired figures, which load cannot bias: "
        "`roislam-stage-bench --paired-passes 0 --paired-slam-passes 1 --frames 250` "
        "(fe_cost_vs_trad).\n\n"
        "| version | extractor | fps | wall time ratio vs traditional | front end (ms/frame) | "
        "front-end ratio vs traditional | peak RSS (MiB) "
        "|\n|---|---|---|---|---|---|---|\n";
}

/** One version and extractor summed over the successful paired entries. */
struct TPairedSums
{
  std::vector<double> front, fps;  //!< per entry, to average
  /** Sums of this version's figures and of traditional's (the entry's first
   *  version) on the same entries. */
  double feV = 0, feT = 0, wallV = 0, wallT = 0, cpuV = 0, cpuT = 0;
  std::string label;  //!< the first entry's label of the version
};

TPairedSums pairedSums(
    const std::vector<TPairedCost>& paired, const std::string& vk, const std::string& f)
{
  TPairedSums s;
  for (const auto& c : paired)
  {
    if (c.feature != f || !c.ok())
      continue;
    for (const auto& v : c.versions)
    {
      if (v.key != vk)
        continue;
      const auto& t = c.versions.front();  // traditional
      s.front.push_back(v.frontEndMsPerFrame);
      s.fps.push_back(v.fps);
      s.feV += v.frontEndMsPerFrame;
      s.feT += t.frontEndMsPerFrame;
      s.wallV += v.wallMsPerFrame;
      s.wallT += t.wallMsPerFrame;
      s.cpuV += v.cpuMsPerFrame;
      s.cpuT += t.cpuMsPerFrame;
      if (s.label.empty())
        s.label = v.label;
    }
  }
  return s;
}

/** One version and extractor of the Test-2 runs: wall time and front end
 *  summed over the sequences where traditional succeeded too. */
struct TUnpairedSums
{
  double sumV = 0, sumT = 0, feV = 0, feT = 0;
  bool any = false, anyFe = false;
};

TUnpairedSums unpairedSums(
    const std::vector<const TRunRecord*>& t2, const std::string& vk, const std::string& f)
{
  TUnpairedSums s;
  for (const auto* r : t2)
  {
    if (r->run.versionKey() != vk || r->run.feature != f || !r->ok)
      continue;
    for (const auto* t : t2)
      if (t->run.mode == "traditional" && t->run.feature == f &&
          t->run.sequence == r->run.sequence && t->ok)
      {
        s.sumV += durationOf(*r);
        s.sumT += durationOf(*t);
        s.any = true;
        const auto fv = r->number("frontend_ms_per_frame");
        const auto ft = t->number("frontend_ms_per_frame");
        if (fv && ft)
        {
          s.feV += *fv;
          s.feT += *ft;
          s.anyFe = true;
        }
      }
  }
  return s;
}

/** Largest peak RSS of the version's Test-2 runs, MiB (the app's figure,
 *  else wait4's); 0 when there is none. */
double peakRssMb(
    const std::vector<const TRunRecord*>& t2, const std::string& vk, const std::string& f)
{
  double rss = 0;
  for (const auto* r : t2)
    if (r->run.versionKey() == vk && r->run.feature == f)
      rss = std::max(rss, r->number("peak_rss_mb").value_or(r->maxRssMb));
  return rss;
}

/** "mean ± std (n=..)" of per-sequence figures (no std for one). */
std::string meanCell(const std::vector<double>& values, int decimals)
{
  const auto ms = *meanStd(values);
  return num(ms.mean, decimals) + (ms.n > 1 ? " ± " + num(ms.std, decimals) : "") +
         " (n=" + std::to_string(ms.n) + ")";
}

std::string ratio(double a, double b)
{
  return b > 0 ? num(a / b, 2) : "n/a";
}
}  // namespace

CSpeedTableWriter::CSpeedTableWriter(std::vector<TPairedCost> paired) : m_paired(std::move(paired))
{
}

void CSpeedTableWriter::render(std::ostream& md, const TRecordList& t2) const
{
  if (m_paired.empty())
    renderUnpaired(md, t2);
  else
    renderPaired(md, t2);
}

void CSpeedTableWriter::renderPaired(std::ostream& md, const TRecordList& t2) const
{
  int passes = 0;
  for (const auto& c : m_paired)
    passes = std::max(passes, c.passes);
  pairedIntroduction(md, passes);
  const std::vector<std::string> feats = pairedFeatures();
  for (const auto& vk : pairedVersionKeys(t2))
    for (const auto& f : feats)
      renderPairedRow(md, t2, vk, f);
  md << "\n";
  renderPairedNotes(md);
}

std::vector<std::string> CSpeedTableWriter::pairedVersionKeys(const TRecordList& t2) const
{
  std::vector<std::string> keys = versionKeys(t2);
  for (const auto& c : m_paired)
    for (const auto& v : c.versions)
      if (std::find(keys.begin(), keys.end(), v.key) == keys.end())
        keys.push_back(v.key);
  return keys;
}

std::vector<std::string> CSpeedTableWriter::pairedFeatures() const
{
  std::vector<std::string> feats;
  for (const auto& f : kFeatures)
    for (const auto& c : m_paired)
      if (c.feature == f && std::find(feats.begin(), feats.end(), f) == feats.end())
        feats.push_back(f);
  for (const auto& c : m_paired)
    if (std::find(feats.begin(), feats.end(), c.feature) == feats.end())
      feats.push_back(c.feature);
  return feats;
}

void CSpeedTableWriter::renderPairedRow(
    std::ostream& md, const TRecordList& t2, const std::string& vk, const std::string& f) const
{
  const TPairedSums s = pairedSums(m_paired, vk, f);
  if (s.front.empty())
    return;
  const double rss = peakRssMb(t2, vk, f);
  // The records' label, unless they do not know the version.
  const std::string recLabel = labelOf(t2, vk);
  md << "| " << (recLabel != vk || s.label.empty() ? recLabel : s.label) << " | "
     << mrpt::system::upperCase(f) << " | " << meanCell(s.front, 1) << " | " << ratio(s.feV, s.feT)
     << " | " << meanCell(s.fps, 2) << " | " << ratio(s.wallV, s.wallT) << " | "
     << ratio(s.cpuV, s.cpuT) << " | " << (rss > 0 ? num(rss, 0) : std::string("n/a")) << " |\n";
}

void CSpeedTableWriter::renderPairedNotes(std::ostream& md) const
{
  bool notes = false;
  for (const auto& c : m_paired)
  {
    const std::string where = c.sequence + ", " + mrpt::system::upperCase(c.feature);
    if (!c.error.empty())
    {
      md << "- " << where << ": paired measurement FAILED: " << oneLine(c.error) << "\n";
      notes = true;
    }
    for (const auto& [key, why] : c.leftOut)
    {
      md << "- " << where << ": " << key << " left out (" << oneLine(why) << ")\n";
      notes = true;
    }
  }
  if (notes)
    md << "\n";
}

void CSpeedTableWriter::renderUnpaired(std::ostream& md, const TRecordList& t2) const
{
  unpairedIntroduction(md);
  const auto feats = featuresOf(t2);
  for (const auto& vk : versionKeys(t2))
    for (const auto& f : feats)
      renderUnpairedRow(md, t2, vk, f);
  md << "\n";
}

void CSpeedTableWriter::renderUnpairedRow(
    std::ostream& md, const TRecordList& t2, const std::string& vk, const std::string& f) const
{
  const TCell fps = cellFor(t2, vk, f, getter("fps"));
  const TCell front = cellFor(t2, vk, f, getter("frontend_ms_per_frame"));
  const TUnpairedSums s = unpairedSums(t2, vk, f);
  md << "| " << labelOf(t2, vk) << " | " << mrpt::system::upperCase(f) << " | "
     << renderCell(fps, 2, true) << " | "
     << (s.any && s.sumT > 0 ? num(s.sumV / s.sumT, 2) : std::string("n/a")) << " | "
     << renderCell(front, 1, true) << " | "
     << (s.anyFe && s.feT > 0 ? num(s.feV / s.feT, 2) : std::string("n/a")) << " | "
     << num(peakRssMb(t2, vk, f), 0) << " |\n";
}
}  // namespace roislam::bench
