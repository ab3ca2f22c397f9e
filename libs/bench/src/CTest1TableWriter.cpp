/* The Test 1 section of report.md (CTest1TableWriter.h). */
#include "CTest1TableWriter.h"

#include <mrpt/system/string_utils.h>
#include <roislam/bench/CReportWriter.h>

#include <array>
#include <map>

#include "ReportTables.h"

namespace roislam::bench
{
using namespace report;

namespace
{
/** The record of one sequence, variant ("" = plain) and extractor, or null. */
const TRunRecord* findVariantRun(
    const std::vector<const TRunRecord*>& recs, const std::string& seq, const std::string& variant,
    const std::string& f)
{
  const TRunRecord* rec = nullptr;
  for (const auto* r : recs)
    if (r->run.sequence == seq && r->run.variant == variant && r->run.feature == f)
      rec = r;
  return rec;
}

/** " (variant)" for a variant's row, "" for the plain run. */
std::string variantSuffix(const std::string& variant)
{
  return variant.empty() ? std::string() : " (" + variant + ")";
}

/** "landmarks / false positives / false negatives" of a Test 1 run, each
 *  value also collected into sums. */
std::string test1Cell(const TRunRecord* rec, std::array<std::vector<double>, 3>& sums)
{
  if (!rec)
    return "—";
  if (!rec->ok)
    return "FAILED";
  const char* keys[3] = {"landmarks", "false_positives", "false_negatives"};
  std::string cell;
  for (int k = 0; k < 3; ++k)
  {
    const auto v = rec->number(keys[k]);
    if (v)
      sums[k].push_back(*v);
    cell += (k ? " / " : "") + optNum(v, 0);
  }
  return cell;
}
}  // namespace

CTest1TableWriter::CTest1TableWriter(const CDissertationReference& reference) : m_ref(reference) {}

void CTest1TableWriter::render(std::ostream& md, const TRecordList& t1) const
{
  md << "## Test 1 — ROI landmark pipeline alone (roi-landmarks)\n\n";
  renderLandmarks(md, t1);
  renderMatches(md, t1);
  renderReidentification(md, t1);
  renderHueVerification(md, t1);
}

void CTest1TableWriter::renderLandmarks(std::ostream& md, const TRecordList& t1) const
{
  const auto feats = featuresOf(t1);
  md << "Landmarks in the database / false positives / false negatives "
        "(n/a: no ground truth for landmark identity).\n\n";
  featureHeader(md, "sequence", feats, "diss.");
  // Per variant ("" = plain) and extractor: the values of the three columns.
  std::map<std::string, std::map<std::string, std::array<std::vector<double>, 3>>> sums;
  const auto variants = distinct(t1, [](const TRunRecord& r) { return r.run.variant; });
  for (const auto& s : distinct(t1, [](const TRunRecord& r) { return r.run.sequence; }))
    for (const auto& v : variants)
    {
      md << "| " << s << variantSuffix(v) << " |";
      const auto id = v.empty() ? m_ref.sequenceId(s) : std::nullopt;
      for (const auto& f : feats)
      {
        md << " " << test1Cell(findVariantRun(t1, s, v, f), sums[v][f]) << " | ";
        std::string dcell = "—";
        if (id)
          if (const auto d = m_ref.test1(*id, f))
            dcell = num((*d)[0], 0) + " / " + num((*d)[1], 0) + " / " + num((*d)[2], 0);
        md << dcell << " |";
      }
      md << "\n";
    }
  for (const auto& v : variants)
  {
    md << "| **mean" << (v.empty() ? "" : ", " + v) << "** |";
    for (const auto& f : feats)
    {
      std::string cell;
      for (int k = 0; k < 3; ++k)
      {
        const auto ms = meanStd(sums[v][f][k]);
        cell += (k ? " / " : "") + (ms ? num(ms->mean, 1) : std::string("n/a"));
      }
      const auto d = v.empty() ? m_ref.test1Average(f) : std::nullopt;
      md << " " << cell << " | "
         << (d ? num((*d)[0], 1) + " / " + num((*d)[1], 1) + " / " + num((*d)[2], 1)
               : std::string("—"))
         << " |";
    }
    md << "\n";
  }
  md << "\n";
}

void CTest1TableWriter::renderMatches(std::ostream& md, const TRecordList& t1) const
{
  md << "Matches per frame, false matches per frame, duration and speed (ROI rejected: frames "
        "whose grey ROI the hue detector did not confirm).\n\n"
        "| sequence | extractor | status | frames with ROI | ROI rejected | matches/frame | false "
        "matches/frame | duration (s) | fps |\n|---|---|---|---|---|---|---|---|---|\n";
  for (const auto* r : t1)
    md << "| " << r->run.sequence << variantSuffix(r->run.variant) << " | "
       << mrpt::system::upperCase(r->run.feature) << " | "
       << (r->ok ? "ok" : "FAILED: " + r->failureReason) << " | "
       << optNum(r->number("frames_with_roi"), 0) << " | "
       << optNum(r->number("frames_rejected_by_hue"), 0) << " | "
       << optNum(r->number("matches_per_frame"), 1) << " | "
       << optNum(r->number("false_matches_per_frame"), 2) << " | "
       << optNum(r->number("duration_s"), 2) << " | " << optNum(r->number("fps"), 2) << " |\n";
  md << "\n";
}

void CTest1TableWriter::renderReidentification(std::ostream& md, const TRecordList& t1) const
{
  md << "Re-identification per extractor (our precision / recall of landmark recalls, mean "
        "over sequences; a recall is true when the landmark's point, carried by the match, "
        "lies within match_radius of its stored position; the ROI-median variant is in each "
        "run's summary.json under alternative_scoring; the dissertation reports its average "
        "true-positive and true-negative rates).\n\n| extractor | precision | recall | diss. TP "
        "rate | diss. TN "
        "rate | fps | diss. fps |\n|---|---|---|---|---|---|---|\n";
  const auto pct = [](std::optional<double> v)
  { return v ? num(100 * *v, 1) + " %" : std::string("—"); };
  for (const auto& f : featuresOf(t1))
    for (const auto& v : distinct(t1, [](const TRunRecord& r) { return r.run.variant; }))
    {
      TCell p, rc, fps;
      for (const auto* r : t1)
      {
        if (r->run.feature != f || r->run.variant != v)
          continue;
        for (auto* c : {&p, &rc, &fps})
          ++c->total;
        if (!r->ok)
        {
          for (auto* c : {&p, &rc, &fps})
            ++c->failed;
          continue;
        }
        if (auto v = r->number("precision"))
          p.values.push_back(*v);
        if (auto v = r->number("recall"))
          rc.values.push_back(*v);
        if (auto v = r->number("fps"))
          fps.values.push_back(*v);
      }
      const bool plain = v.empty();
      md << "| " << mrpt::system::upperCase(f) << variantSuffix(v) << " | "
         << renderCell(p, 3, true) << " | " << renderCell(rc, 3, true) << " | "
         << (plain ? pct(m_ref.test1TruePositiveRate(f)) : std::string("—")) << " | "
         << (plain ? pct(m_ref.test1TrueNegativeRate(f)) : std::string("—")) << " | "
         << renderCell(fps, 2, true) << " | "
         << (plain ? optNum(m_ref.test1Fps(f), 2) : std::string("—")) << " |\n";
    }
  md << "\n";
}

void CTest1TableWriter::renderHueVerification(std::ostream& md, const TRecordList& t1) const
{
  bool any = false;
  for (const auto* r : t1)
    any = any || r->run.variant == "hue";
  if (!any)
    return;
  md << "### ROI verified by the hue detector (variant hue, [RoiDetector] verify_hue)\n\n"
        "Each cell: without → with verification.\n\n"
        "| sequence | extractor | landmarks | precision | recall | frames with ROI |\n"
        "|---|---|---|---|---|---|\n";
  for (const auto& s : distinct(t1, [](const TRunRecord& r) { return r.run.sequence; }))
    for (const auto& f : featuresOf(t1))
    {
      const TRunRecord* a = findVariantRun(t1, s, "", f);
      const TRunRecord* b = findVariantRun(t1, s, "hue", f);
      if (!a && !b)
        continue;
      const auto pair = [&](const char* key, int decimals)
      {
        const auto get = [&](const TRunRecord* r)
        { return r && r->ok ? optNum(r->number(key), decimals) : std::string("n/a"); };
        return get(a) + " → " + get(b);
      };
      md << "| " << s << " | " << mrpt::system::upperCase(f) << " | " << pair("landmarks", 0)
         << " | " << pair("precision", 3) << " | " << pair("recall", 3) << " | "
         << pair("frames_with_roi", 0) << " |\n";
    }
  md << "\n";
}
}  // namespace roislam::bench
