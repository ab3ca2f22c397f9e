#include "roislam/bench/CReportWriter.h"

#include <mrpt/system/string_utils.h>
#include <roislam/bench/ProcessUtils.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>

namespace roislam::bench
{
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
const std::vector<std::string> kFeatures{"surf", "sift", "orb"};

std::string num(double v, int decimals)
{
  std::ostringstream ss;
  ss << std::fixed << std::setprecision(decimals) << v;
  return ss.str();
}

std::string optNum(const std::optional<double>& v, int decimals)
{
  return v ? num(*v, decimals) : "n/a";
}

/** Ordered distinct values of f(record). */
template <class F>
std::vector<std::string> distinct(const std::vector<const TRunRecord*>& recs, F f)
{
  std::vector<std::string> out;
  for (const auto* r : recs)
  {
    const std::string v = f(*r);
    if (std::find(out.begin(), out.end(), v) == out.end())
      out.push_back(v);
  }
  return out;
}

/** Features present, in the dissertation's order SURF, SIFT, ORB. */
std::vector<std::string> featuresOf(const std::vector<const TRunRecord*>& recs)
{
  std::vector<std::string> out;
  for (const auto& f : kFeatures)
    for (const auto* r : recs)
      if (r->run.feature == f)
      {
        out.push_back(f);
        break;
      }
  return out;
}

int modeRank(const std::string& mode)
{
  if (mode == "traditional")
    return 0;
  if (mode == "roi_small")
    return 1;
  if (mode == "roi_big")
    return 2;
  return 3;
}

/** Aggregated figure over sequences for one table cell. */
struct TCell
{
  std::vector<double> values;
  std::size_t failed = 0, total = 0, missingValue = 0;
};

std::string renderCell(const TCell& c, int decimals, bool withStd)
{
  if (c.total == 0)
    return "—";
  if (c.values.empty())
  {
    if (c.failed == c.total)
      return "FAILED (" + std::to_string(c.failed) + "/" + std::to_string(c.total) + ")";
    return "n/a";
  }
  const auto ms = *meanStd(c.values);
  std::string s = num(ms.mean, decimals);
  if (withStd && ms.n > 1)
    s += " ± " + num(ms.std, decimals);
  std::string note = "n=" + std::to_string(ms.n);
  if (c.failed)
    note += ", " + std::to_string(c.failed) + " failed";
  return s + " (" + note + ")";
}

double durationOf(const TRunRecord& r)
{
  if (auto w = r.number("wall_s"))
    return *w;
  if (auto d = r.number("duration_s"))
    return *d;
  return r.wallS;
}
}  // namespace

CReportWriter::CReportWriter(const TOptions& options, const CDissertationReference& reference)
    : m_options(options), m_ref(reference)
{
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

  // Sequences and their mapping.
  std::vector<const TRunRecord*> all;
  for (const auto& r : records)
    all.push_back(&r);
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

  const auto select = [&](int test)
  {
    std::vector<const TRunRecord*> out;
    for (const auto* r : all)
      if (r->run.test == test)
        out.push_back(r);
    return out;
  };

  // ---------------- Test 1 ----------------
  const auto t1 = select(1);
  if (!t1.empty())
  {
    const auto feats = featuresOf(t1);
    md << "## Test 1 — ROI landmark pipeline alone (roi-landmarks)\n\n";
    md << "Landmarks in the database / false positives / false negatives "
          "(n/a: no ground truth for landmark identity).\n\n| sequence |";
    for (const auto& f : feats)
      md << " " << mrpt::system::upperCase(f) << " | " << mrpt::system::upperCase(f) << " diss. |";
    md << "\n|---|";
    for (std::size_t k = 0; k < feats.size(); ++k)
      md << "---|---|";
    md << "\n";
    std::map<std::string, std::array<std::vector<double>, 3>> sums;
    for (const auto& s : distinct(t1, [](const TRunRecord& r) { return r.run.sequence; }))
    {
      md << "| " << s << " |";
      const auto id = m_ref.sequenceId(s);
      for (const auto& f : feats)
      {
        const TRunRecord* rec = nullptr;
        for (const auto* r : t1)
          if (r->run.sequence == s && r->run.feature == f)
            rec = r;
        std::string cell = "—";
        if (rec && !rec->ok)
          cell = "FAILED";
        else if (rec)
        {
          const char* keys[3] = {"landmarks", "false_positives", "false_negatives"};
          cell.clear();
          for (int k = 0; k < 3; ++k)
          {
            const auto v = rec->number(keys[k]);
            if (v)
              sums[f][k].push_back(*v);
            cell += (k ? " / " : "") + optNum(v, 0);
          }
        }
        std::string dcell = "—";
        if (id)
          if (const auto d = m_ref.test1(*id, f))
            dcell = num((*d)[0], 0) + " / " + num((*d)[1], 0) + " / " + num((*d)[2], 0);
        md << " " << cell << " | " << dcell << " |";
      }
      md << "\n";
    }
    md << "| **mean** |";
    for (const auto& f : feats)
    {
      std::string cell;
      for (int k = 0; k < 3; ++k)
      {
        const auto ms = meanStd(sums[f][k]);
        cell += (k ? " / " : "") + (ms ? num(ms->mean, 1) : std::string("n/a"));
      }
      const auto d = m_ref.test1Average(f);
      md << " " << cell << " | "
         << (d ? num((*d)[0], 1) + " / " + num((*d)[1], 1) + " / " + num((*d)[2], 1)
               : std::string("—"))
         << " |";
    }
    md << "\n\n";

    md << "Matches per frame, false matches per frame, duration and speed.\n\n"
          "| sequence | extractor | status | frames with ROI | matches/frame | false "
          "matches/frame | duration (s) | fps |\n|---|---|---|---|---|---|---|---|\n";
    for (const auto* r : t1)
      md << "| " << r->run.sequence << " | " << mrpt::system::upperCase(r->run.feature) << " | "
         << (r->ok ? "ok" : "FAILED: " + r->failureReason) << " | "
         << optNum(r->number("frames_with_roi"), 0) << " | "
         << optNum(r->number("matches_per_frame"), 1) << " | "
         << optNum(r->number("false_matches_per_frame"), 2) << " | "
         << optNum(r->number("duration_s"), 2) << " | " << optNum(r->number("fps"), 2) << " |\n";
    md << "\n";

    md << "Re-identification per extractor (our precision / recall of landmark recalls, mean "
          "over sequences; a recall is true when the landmark's point, carried by the match, "
          "lies within match_radius of its stored position; the ROI-median variant is in each "
          "run's summary.json under alternative_scoring; the dissertation reports its average "
          "true-positive and true-negative rates).\n\n| extractor | precision | recall | diss. TP "
          "rate | diss. TN "
          "rate | fps | diss. fps |\n|---|---|---|---|---|---|---|\n";
    for (const auto& f : feats)
    {
      TCell p, rc, fps;
      for (const auto* r : t1)
      {
        if (r->run.feature != f)
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
      const auto pct = [](std::optional<double> v)
      { return v ? num(100 * *v, 1) + " %" : std::string("—"); };
      md << "| " << mrpt::system::upperCase(f) << " | " << renderCell(p, 3, true) << " | "
         << renderCell(rc, 3, true) << " | " << pct(m_ref.test1TruePositiveRate(f)) << " | "
         << pct(m_ref.test1TrueNegativeRate(f)) << " | " << renderCell(fps, 2, true) << " | "
         << optNum(m_ref.test1Fps(f), 2) << " |\n";
    }
    md << "\n";
  }

  // ---------------- Tests 2 and 3 ----------------
  const auto versionKeys = [&](const std::vector<const TRunRecord*>& recs)
  {
    auto keys = distinct(recs, [](const TRunRecord& r) { return r.run.versionKey(); });
    std::stable_sort(
        keys.begin(), keys.end(),
        [](const std::string& a, const std::string& b)
        { return modeRank(a.substr(0, a.find('/'))) < modeRank(b.substr(0, b.find('/'))); });
    return keys;
  };
  const auto cellFor = [&](const std::vector<const TRunRecord*>& recs, const std::string& vk,
                           const std::string& f,
                           const std::function<std::optional<double>(const TRunRecord&)>& get)
  {
    TCell c;
    for (const auto* r : recs)
    {
      if (r->run.versionKey() != vk || r->run.feature != f)
        continue;
      ++c.total;
      if (!r->ok)
      {
        ++c.failed;
        continue;
      }
      if (auto v = get(*r))
        c.values.push_back(*v);
      else
        ++c.missingValue;
    }
    return c;
  };
  const auto labelOf = [&](const std::vector<const TRunRecord*>& recs, const std::string& vk)
  {
    for (const auto* r : recs)
      if (r->run.versionKey() == vk)
        return versionLabel(*r);
    return vk;
  };
  const auto getter = [](const std::string& key)
  { return [key](const TRunRecord& r) { return r.number(key); }; };

  const auto t2 = select(2);
  if (!t2.empty())
  {
    const auto feats = featuresOf(t2);
    const auto keys = versionKeys(t2);
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
    // One table: a row per version, per extractor our cell and the
    // dissertation's value (ref(mode, feature), "—" when it has none).
    const auto versionTable =
        [&](const std::string& title, const std::string& refLabel, int decimals,
            const std::function<std::optional<double>(const TRunRecord&)>& get,
            const std::function<std::string(const std::string&, const std::string&)>& ref)
    {
      md << "### " << title << "\n\n| version |";
      for (const auto& f : feats)
        md << " " << mrpt::system::upperCase(f) << " | " << mrpt::system::upperCase(f) << " "
           << refLabel << " |";
      md << "\n|---|";
      for (std::size_t k = 0; k < feats.size(); ++k)
        md << "---|---|";
      md << "\n";
      for (const auto& vk : keys)
      {
        const std::string mode = vk.substr(0, vk.find('/'));
        md << "| " << labelOf(t2, vk) << " |";
        for (const auto& f : feats)
          md << " " << renderCell(cellFor(t2, vk, f, get), decimals, true) << " | " << ref(mode, f)
             << " |";
        md << "\n";
      }
      md << "\n";
    };
    for (const auto& m : metrics)
      versionTable(
          m.title, "diss.", m.decimals, getter(m.key),
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
    versionTable(
        "Duration per run (s; diss. in minutes on full sequences)", "diss. (min)", 1,
        [](const TRunRecord& r) { return std::optional<double>(durationOf(r)); },
        [&](const std::string& mode, const std::string& f)
        {
          const auto d = m_ref.scalar(2, mode, f, "duration_min");
          return d ? num(*d, 1) : std::string("—");
        });

    md << "### Per sequence: ATE RMSE (m) / duration (s)\n\n| sequence | version |";
    for (const auto& f : feats)
      md << " " << mrpt::system::upperCase(f) << " |";
    md << "\n|---|---|";
    for (std::size_t k = 0; k < feats.size(); ++k)
      md << "---|";
    md << "\n";
    for (const auto& s : distinct(t2, [](const TRunRecord& r) { return r.run.sequence; }))
      for (const auto& vk : keys)
      {
        md << "| " << s << " | " << labelOf(t2, vk) << " |";
        for (const auto& f : feats)
        {
          const TRunRecord* rec = nullptr;
          for (const auto* r : t2)
            if (r->run.sequence == s && r->run.versionKey() == vk && r->run.feature == f)
              rec = r;
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
          for (char& c : cell)
            if (c == '|' || c == '\n')
              c = ' ';
          md << " " << cell << " |";
        }
        md << "\n";
      }
    md << "\n";
  }

  const auto t3 = select(3);
  if (!t3.empty())
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
         << renderCell(
                cellFor(t3, vk, f, [](const TRunRecord& r) { return durationOf(r); }), 1, true)
         << " | " << ref("duration_min", 2) << " |\n";
    }
    md << "\n";
  }

  // ---------------- Speed ----------------
  if (!t2.empty())
  {
    md << "## Speed (Test 2 runs, measured in this benchmark)\n\n"
          "fps = frames / wall time of the app (summary.json); ratio = sum of this version's "
          "wall time over the sum of the traditional version's, on the sequences where both "
          "succeeded; peak memory = largest peak RSS (app's figure, else wait4's). Each figure "
          "comes from one run: on a shared machine single runs vary by 10-20 %, so ratios "
          "within that band are not differences; `roislam-stage-bench --paired-passes 2 "
          "--benchmark_filter=FrontEnd` interleaves the versions frame by frame for a robust "
          "ratio.\n\n"
          "| version | extractor | fps | wall time ratio vs traditional | peak RSS (MiB) "
          "|\n|---|---|---|---|---|\n";
    const auto feats = featuresOf(t2);
    for (const auto& vk : versionKeys(t2))
      for (const auto& f : feats)
      {
        const TCell fps = cellFor(t2, vk, f, getter("fps"));
        double sumV = 0, sumT = 0, rss = 0;
        bool any = false;
        for (const auto* r : t2)
        {
          if (r->run.versionKey() != vk || r->run.feature != f)
            continue;
          rss = std::max(rss, r->number("peak_rss_mb").value_or(r->maxRssMb));
          if (!r->ok)
            continue;
          for (const auto* t : t2)
            if (t->run.mode == "traditional" && t->run.feature == f &&
                t->run.sequence == r->run.sequence && t->ok)
            {
              sumV += durationOf(*r);
              sumT += durationOf(*t);
              any = true;
            }
        }
        md << "| " << labelOf(t2, vk) << " | " << mrpt::system::upperCase(f) << " | "
           << renderCell(fps, 2, true) << " | "
           << (any && sumT > 0 ? num(sumV / sumT, 2) : std::string("n/a")) << " | " << num(rss, 0)
           << " |\n";
      }
    md << "\n";
  }

  // ---------------- Failures ----------------
  md << "## Failed runs\n\n";
  if (nFailed == 0)
    md << "None.\n\n";
  for (const auto& r : records)
    if (!r.ok)
    {
      std::string reason = r.failureReason;
      for (char& c : reason)
        if (c == '\n')
          c = ' ';
      md << "- `" << r.run.id << "`: " << reason << "\n";
    }
  if (nFailed)
    md << "\n";
  if (m_ref.data().contains("failures"))
    md << "Dissertation: " << m_ref.data().value("failures", "") << "\n\n";

  if (!m_options.charts.empty())
  {
    md << "## Charts\n\n";
    for (const auto& c : m_options.charts)
      md << "![" << c << "](" << c << ")\n\n";
  }
  return md.str();
}

void CReportWriter::write(const std::vector<TRunRecord>& records, const std::string& file) const
{
  writeFileAtomically(file, render(records));
}
}  // namespace roislam::bench
