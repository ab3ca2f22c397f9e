#include "roislam/bench/CReportWriter.h"

#include <roislam/bench/ProcessUtils.h>

#include <cmath>
#include <sstream>

#include "CSpeedTableWriter.h"
#include "CTest1TableWriter.h"
#include "CTrajectoryTableWriter.h"
#include "ReferenceTable.h"
#include "ReportTables.h"

namespace roislam::bench
{
using namespace report;

std::optional<TMeanStd> meanStd(const std::vector<double>& values)
{
  if (values.empty())
    return std::nullopt;
  TMeanStd r;
  r.n = values.size();
  for (double v : values)
    r.mean += v;
  r.mean /= r.n;
  if (r.n > 1)
  {
    double s = 0;
    for (double v : values)
      s += (v - r.mean) * (v - r.mean);
    r.std = std::sqrt(s / (r.n - 1));
  }
  return r;
}

namespace
{
/** Records of one test, in plan order. */
std::vector<const TRunRecord*> select(const std::vector<const TRunRecord*>& all, int test)
{
  std::vector<const TRunRecord*> out;
  for (const auto* r : all)
    if (r->run.test == test)
      out.push_back(r);
  return out;
}
}  // namespace

CReportWriter::CReportWriter(const TOptions& options, const CDissertationReference& reference)
    : m_options(options), m_ref(reference)
{
  if (!m_options.pairedCostFile.empty())
    m_paired = loadPairedCosts(m_options.pairedCostFile);
}

std::string CReportWriter::versionLabel(const TRunRecord& rec)
{
  const auto& m = rec.run.mode;
  std::string base = m == "traditional" ? "traditional"
                     : m == "roi_small" ? "small ROI"
                     : m == "roi_big"   ? "big ROI"
                                        : m;
  if (rec.run.variant.empty())
    return base;
  if (rec.run.variant == "strict")
    return base + " — strict (dissertation's behaviour)";
  if (rec.run.variant == "fallback")
    return base + " + fallback (**ours**)";
  if (rec.run.variant == "roicap")
    return base + " + fallback, N features in the ROI (**ours**)";
  return base + " — variant " + rec.run.variant + " (**ours**: " + rec.run.variantLabel + ")";
}

std::string CReportWriter::render(const std::vector<TRunRecord>& records) const
{
  std::ostringstream md;
  std::vector<const TRunRecord*> all;
  for (const auto& r : records)
    all.push_back(&r);
  renderIntroduction(md, records);
  renderSequences(md, all);
  const auto t1 = select(all, 1);
  if (!t1.empty())
    CTest1TableWriter(m_ref).render(md, t1);
  const CTrajectoryTableWriter trajectories(m_ref);
  const auto t2 = select(all, 2);
  if (!t2.empty())
    trajectories.renderTest2(md, t2);
  const auto t3 = select(all, 3);
  if (!t3.empty())
    trajectories.renderTest3(md, t3);
  const auto t4 = select(all, 4);
  if (!t4.empty())
    trajectories.renderTest4(md, t4);
  const auto reference = select(all, 0);
  if (!reference.empty())
    report::renderReference(md, reference, all);
  if (!t2.empty())
    CSpeedTableWriter(m_paired).render(md, t2);
  renderFailures(md, records);
  if (!m_options.charts.empty())
  {
    md << "## Charts\n\n";
    for (const auto& c : m_options.charts)
      md << "![" << c << "](" << c << ")\n\n";
  }
  return md.str();
}

void CReportWriter::renderIntroduction(
    std::ostream& md, const std::vector<TRunRecord>& records) const
{
  std::size_t nOk = 0, nFailed = 0;
  for (const auto& r : records)
    (r.ok ? nOk : nFailed)++;
  md << "# roi-bench report: the dissertation's Tests 1–3, reproduced\n\n";
  md << "Runs: " << records.size() << " (" << nOk << " succeeded, " << nFailed << " failed); up to "
     << m_options.jobs << " run(s) in parallel, so timings are per run under that load. "
     << "Every figure comes from the run's summary.json (see results.csv for every run, its "
        "figures and its exact command). Dissertation figures (\"diss.\") are from its text; "
        "its sequences are full TUM sequences on a Core i7, so absolute durations are not "
        "comparable with ours.\n\n";
}

void CReportWriter::renderSequences(std::ostream& md, const TRecordList& all) const
{
  const auto seqs = distinct(all, [](const TRunRecord& r) { return r.run.sequence; });
  md << "## Sequences\n\n| sequence | dissertation's sequence | frames |\n|---|---|---|\n";
  for (const auto& s : seqs)
  {
    std::optional<double> frames;
    for (const auto* r : all)
      if (r->run.sequence == s && r->number("frames"))
      {
        frames = r->number("frames");
        break;
      }
    const auto id = m_ref.sequenceId(s);
    md << "| " << s << " | "
       << (id ? std::to_string(*id) + " (" + m_ref.sequenceShortName(*id) + ")"
              : std::string("— (compared with the dissertation's averages)"))
       << " | " << optNum(frames, 0) << " |\n";
  }
  md << "\n";
}

void CReportWriter::renderFailures(std::ostream& md, const std::vector<TRunRecord>& records) const
{
  md << "## Failed runs\n\n";
  std::size_t nFailed = 0;
  for (const auto& r : records)
    if (!r.ok)
    {
      ++nFailed;
      std::string reason = r.failureReason;
      for (char& c : reason)
        if (c == '\n')
          c = ' ';
      md << "- `" << r.run.id << "`: " << reason << "\n";
    }
  if (nFailed == 0)
    md << "None.\n\n";
  else
    md << "\n";
  if (m_ref.data().contains("failures"))
    md << "Dissertation: " << m_ref.data().value("failures", "") << "\n\n";
}

void CReportWriter::write(const std::vector<TRunRecord>& records, const std::string& file) const
{
  writeFileAtomically(file, render(records));
}
}  // namespace roislam::bench
