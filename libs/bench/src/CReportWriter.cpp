#include "roislam/bench/CReportWriter.h"

#include <mrpt/system/string_utils.h>
#include <roislam/bench/ProcessUtils.h>

#include <array>
#include <cmath>
#include <map>
#include <sstream>

#include "CSpeedTableWriter.h"
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
std::string optNum(const std::optional<double>& v, int decimals)
{
  return v ? num(*v, decimals) : "n/a";
}

/** Records of one test, in plan order. */
std::vector<const TRunRecord*> select(const std::vector<const TRunRecord*>& all, int test)
{
  std::vector<const TRunRecord*> out;
  for (const auto* r : all)
    if (r->run.test == test)
      out.push_back(r);
  return out;
}

/** The record of one sequence, version and extractor, or null. */
const TRunRecord* findRun(
    const std::vector<const TRunRecord*>& recs, const std::string& seq, const std::string& vk,
    const std::string& f)
{
  const TRunRecord* rec = nullptr;
  for (const auto* r : recs)
    if (r->run.sequence == seq && r->run.versionKey() == vk && r->run.feature == f)
      rec = r;
  return rec;
}

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

/** Table header "| first |" + per extractor " F | F <refLabel> |" and its rule. */
void featureHeader(
    std::ostream& md, const std::string& first, const std::vector<std::string>& feats,
    const std::string& refLabel)
{
  md << "| " << first << " |";
  for (const auto& f : feats)
    md << " " << mrpt::system::upperCase(f) << " | " << mrpt::system::upperCase(f) << " "
       << refLabel << " |";
  md << "\n|---|";
  for (std::size_t k = 0; k < feats.size(); ++k)
    md << "---|---|";
  md << "\n";
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
  {
    md << "## Test 1 — ROI landmark pipeline alone (roi-landmarks)\n\n";
    renderTest1Landmarks(md, t1);
    renderTest1Matches(md, t1);
    renderTest1Reidentification(md, t1);
    renderHueVerification(md, t1);
  }
  const auto t2 = select(all, 2);
  if (!t2.empty())
    renderTest2(md, t2);
  const auto t3 = select(all, 3);
  if (!t3.empty())
    renderTest3(md, t3);
  const auto t4 = select(all, 4);
  if (!t4.empty())
    renderTest4(md, t4);
  const auto reference = select(all, 0);
  if (!reference.empty())
    renderReference(md, reference, all);
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

void CReportWriter::renderTest1Landmarks(std::ostream& md, const TRecordList& t1) const
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

void CReportWriter::renderTest1Matches(std::ostream& md, const TRecordList& t1) const
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

void CReportWriter::renderTest1Reidentification(std::ostream& md, const TRecordList& t1) const
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

void CReportWriter::renderHueVerification(std::ostream& md, const TRecordList& t1) const
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

void CReportWriter::renderVersionTable(
    std::ostream& md, const TRecordList& t2, const std::string& title, const std::string& refLabel,
    int decimals, const TGetter& get, const TReference& ref) const
{
  const auto feats = featuresOf(t2);
  md << "### " << title << "\n\n";
  featureHeader(md, "version", feats, refLabel);
  for (const auto& vk : versionKeys(t2))
  {
    const std::string mode = vk.substr(0, vk.find('/'));
    md << "| " << labelOf(t2, vk) << " |";
    for (const auto& f : feats)
      md << " " << renderCell(cellFor(t2, vk, f, get), decimals, true) << " | " << ref(mode, f)
         << " |";
    md << "\n";
  }
  md << "\n";
}

void CReportWriter::renderTest2(std::ostream& md, const TRecordList& t2) const
{
  const int cap = t2.front()->run.maxFeatures;
  md << "## Test 2 — inside RGB-D SLAM (roi-graphslam), features capped at " << cap << "\n\n";
  md << "Mean ± std over sequences (sample std); failed runs are counted, not averaged. "
        "Rows marked **ours** are our improvements; the strict rows reproduce the "
        "dissertation's behaviour.\n\n";
  struct TMetric
  {
    std::string title, key, refKey;
    int decimals;
    bool refHasStd;
  };
  const std::vector<TMetric> metrics{
      {"Absolute trajectory error, RMSE (m)", "ate_rmse", "ate", 4, true},
      {"Relative pose error, translation RMSE (m)", "rpe_trans_rmse", "rpe_trans", 4, false},
      {"Relative pose error, rotation RMSE (deg)", "rpe_rot_rmse_deg", "rpe_rot_deg", 3, false}};
  // One table per metric: a row per version, per extractor our cell and the
  // dissertation's value (ref(mode, feature), "—" when it has none).
  for (const auto& m : metrics)
    renderVersionTable(
        md, t2, m.title, "diss.", m.decimals, getter(m.key),
        [&](const std::string& mode, const std::string& f)
        {
          if (m.refHasStd)
          {
            if (auto a = m_ref.ate(2, mode, f))
              return num(a->first, 3) + " ± " + num(a->second, 3);
          }
          else if (auto v = m_ref.scalar(2, mode, f, m.refKey))
            return num(*v, 3);
          return std::string("—");
        });
  renderVersionTable(
      md, t2, "Duration per run (s; diss. in minutes on full sequences)", "diss. (min)", 1,
      [](const TRunRecord& r) { return std::optional<double>(durationOf(r)); },
      [&](const std::string& mode, const std::string& f)
      {
        const auto d = m_ref.scalar(2, mode, f, "duration_min");
        return d ? num(*d, 1) : std::string("—");
      });
  renderTest2PerSequence(md, t2);
}

void CReportWriter::renderTest2PerSequence(std::ostream& md, const TRecordList& t2) const
{
  const auto feats = featuresOf(t2);
  md << "### Per sequence: ATE RMSE (m) / duration (s)\n\n| sequence | version |";
  for (const auto& f : feats)
    md << " " << mrpt::system::upperCase(f) << " |";
  md << "\n|---|---|";
  for (std::size_t k = 0; k < feats.size(); ++k)
    md << "---|";
  md << "\n";
  const auto keys = versionKeys(t2);
  for (const auto& s : distinct(t2, [](const TRunRecord& r) { return r.run.sequence; }))
    for (const auto& vk : keys)
    {
      md << "| " << s << " | " << labelOf(t2, vk) << " |";
      for (const auto& f : feats)
      {
        const TRunRecord* rec = findRun(t2, s, vk, f);
        std::string cell = "—";
        if (rec && !rec->ok)
          cell = "FAILED (" + rec->failureReason + ")";
        else if (rec)
        {
          cell = optNum(rec->number("ate_rmse"), 4) + " / " + num(durationOf(*rec), 1);
          // Frames where the ROI front end fell back to the whole image (our improvement).
          if (const auto fb = rec->number("fallback_frames"); fb && *fb > 0)
            cell += " (fallback " + num(*fb, 0) + " frames)";
        }
        md << " " << oneLine(cell) << " |";
      }
      md << "\n";
    }
  md << "\n";
}

void CReportWriter::renderTest3(std::ostream& md, const TRecordList& t3) const
{
  const std::string f = t3.front()->run.feature;
  const int cap = t3.front()->run.maxFeatures;
  md << "## Test 3 — reduced features: " << mrpt::system::upperCase(f) << " capped at " << cap
     << "\n\n";
  md << "| version | ATE RMSE (m) | diss. | RPE trans (m) | diss. | RPE rot (deg) | diss. | "
        "duration (s) | diss. (min) |\n|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& vk : versionKeys(t3))
  {
    const std::string mode = vk.substr(0, vk.find('/'));
    const auto a = m_ref.ate(3, mode, f);
    const auto ref = [&](const std::string& k, int d)
    {
      const auto v = m_ref.scalar(3, mode, f, k);
      return v ? num(*v, d) : std::string("—");
    };
    md << "| " << labelOf(t3, vk) << " | "
       << renderCell(cellFor(t3, vk, f, getter("ate_rmse")), 4, true) << " | "
       << (a ? num(a->first, 3) + " ± " + num(a->second, 3) : std::string("—")) << " | "
       << renderCell(cellFor(t3, vk, f, getter("rpe_trans_rmse")), 4, true) << " | "
       << ref("rpe_trans", 3) << " | "
       << renderCell(cellFor(t3, vk, f, getter("rpe_rot_rmse_deg")), 3, true) << " | "
       << ref("rpe_rot_deg", 2) << " | "
       << renderCell(cellFor(t3, vk, f, [](const TRunRecord& r) { return durationOf(r); }), 1, true)
       << " | " << ref("duration_min", 2) << " |\n";
  }
  md << "\n";
}

void CReportWriter::renderTest4(std::ostream& md, const TRecordList& t4) const
{
  md << "## Test 4 — EKF-SLAM on ROI landmarks (MRPT kf-slam), odometry alone, graph SLAM\n\n"
        "EKF: roi-landmarks --kf-slam (MRPT's CRangeBearingKFSLAM on our landmark observations "
        "and front-end odometry); odometry: the same front end alone (from the same run); graph "
        "SLAM: roi-graphslam with that front end (big ROI). ATE RMSE (m), RPE translation (m) / "
        "rotation (deg).\n\n"
        "| sequence | extractor | EKF ATE | odometry ATE | graph SLAM ATE | EKF RPE | odometry "
        "RPE | graph SLAM RPE |\n|---|---|---|---|---|---|---|---|\n";
  std::array<std::vector<double>, 3> ates;
  for (const auto& s : distinct(t4, [](const TRunRecord& r) { return r.run.sequence; }))
    for (const auto& f : featuresOf(t4))
    {
      const TRunRecord* ekf = findRun(t4, s, "kf_slam", f);
      const TRunRecord* graph = findRun(t4, s, "graph_slam", f);
      if (!ekf && !graph)
        continue;
      const auto figure = [](const TRunRecord* r, const std::string& key, int decimals,
                             std::vector<double>* collect = nullptr)
      {
        if (!r)
          return std::string("—");
        if (!r->ok)
          return std::string("FAILED");
        const auto v = r->number(key);
        if (v && collect)
          collect->push_back(*v);
        return optNum(v, decimals);
      };
      const auto rpe = [&](const TRunRecord* r, const std::string& prefix)
      {
        return figure(r, prefix + "rpe_trans_rmse", 4) + " / " +
               figure(r, prefix + "rpe_rot_rmse_deg", 2);
      };
      md << "| " << s << " | " << mrpt::system::upperCase(f) << " | "
         << figure(ekf, "kf_slam.ate_rmse", 4, &ates[0]) << " | "
         << figure(ekf, "kf_slam.odometry_ate_rmse", 4, &ates[1]) << " | "
         << figure(graph, "ate_rmse", 4, &ates[2]) << " | " << rpe(ekf, "kf_slam.") << " | "
         << rpe(ekf, "kf_slam.odometry_") << " | " << rpe(graph, "") << " |\n";
    }
  md << "| **mean** | |";
  for (const auto& a : ates)
  {
    const auto ms = meanStd(a);
    md << " " << (ms ? num(ms->mean, 4) + " (n=" + std::to_string(ms->n) + ")" : "n/a") << " |";
  }
  md << " | | |\n\n";
}

void CReportWriter::renderReference(
    std::ostream& md, const TRecordList& ref, const TRecordList& all) const
{
  md << "## Reference: OpenCV's cv::rgbd odometry, frame to frame\n\n"
        "cv-odometry runs OpenCV's RgbdOdometry (photometric), ICPOdometry (depth) and "
        "RgbdICPOdometry (both) with OpenCV's default parameters, each frame against the "
        "previous one, no keyframes, no loop closure, on the same frames with the same "
        "intrinsics (a distorted camera is undistorted first). A sequence where the "
        "reference fails too is hard; one where it beats us points to our system. Below each "
        "sequence's reference rows, our best and worst trajectory on it (Tests 2-4); our ms "
        "per frame is the whole run's wall time per frame, the reference's its odometry "
        "alone.\n\n"
        "| sequence | method | ATE RMSE (m) | RPE trans (m) | RPE rot (deg) | ms per frame | "
        "failed frames |\n|---|---|---|---|---|---|---|\n";
  const auto msPerFrame = [](const TRunRecord& r) -> std::optional<double>
  {
    if (auto ms = r.number("ms_per_frame"))
      return ms;
    const auto frames = r.number("frames");
    if (!frames || *frames <= 0)
      return std::nullopt;
    return 1000 * durationOf(r) / *frames;
  };
  const auto row = [&](const std::string& seq, const std::string& label, const TRunRecord& r)
  {
    md << "| " << seq << " | " << label << " | ";
    if (!r.ok)
    {
      md << oneLine("FAILED: " + r.failureReason) << " | | | | |\n";
      return;
    }
    md << optNum(r.number("ate_rmse"), 4) << " | " << optNum(r.number("rpe_trans_rmse"), 4) << " | "
       << optNum(r.number("rpe_rot_rmse_deg"), 3) << " | " << optNum(msPerFrame(r), 1) << " | "
       << optNum(r.number("failed_frames"), 0) << " |\n";
  };
  for (const auto& s : distinct(ref, [](const TRunRecord& r) { return r.run.sequence; }))
  {
    for (const auto* r : ref)
      if (r->run.sequence == s)
        row(s,
            "cv::rgbd " + r->run.mode.substr(3) + " (" +
                r->summary.value("opencv_class", std::string("reference")) + ")",
            *r);
    const TRunRecord *best = nullptr, *worst = nullptr;
    for (const auto* r : all)
    {
      const auto ate = r->number("ate_rmse");
      if (r->run.test < 2 || r->run.sequence != s || !r->ok || !ate)
        continue;
      if (!best || *ate < *best->number("ate_rmse"))
        best = r;
      if (!worst || *ate > *worst->number("ate_rmse"))
        worst = r;
    }
    const auto ours = [&](const char* which, const TRunRecord* r)
    {
      row(s,
          std::string("ours, ") + which + ": test " + std::to_string(r->run.test) + " " +
              versionLabel(*r) + " " + mrpt::system::upperCase(r->run.feature),
          *r);
    };
    if (best)
      ours("best", best);
    if (worst && worst != best)
      ours("worst", worst);
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
