/* The Test 2, 3 and 4 sections of report.md (CTrajectoryTableWriter.h). */
#include "CTrajectoryTableWriter.h"

#include <mrpt/system/string_utils.h>
#include <roislam/bench/CReportWriter.h>

#include <algorithm>
#include <array>

#include "ReportTables.h"

namespace roislam::bench
{
using namespace report;

namespace
{
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

}  // namespace

CTrajectoryTableWriter::CTrajectoryTableWriter(const CDissertationReference& reference)
    : m_ref(reference)
{
}

void CTrajectoryTableWriter::renderVersionTable(
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

void CTrajectoryTableWriter::renderTest2(std::ostream& md, const TRecordList& t2) const
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
  renderTest2EdgeChi2(md, t2);
}

void CTrajectoryTableWriter::renderTest2EdgeChi2(std::ostream& md, const TRecordList& t2) const
{
  const bool any = std::any_of(
      t2.begin(), t2.end(), [](const TRunRecord* r) { return r->number("edge_chi2.median"); });
  if (!any)
    return;
  renderPerSequenceTable(
      md, t2,
      "### Per sequence: are the graph's edges honest?\n\n"
      "Median chi² of the graph's edges against the ground truth's relative poses (6 degrees "
      "of freedom: an honest information reads about 5.35), then the same with the ground "
      "truth's own noise, measured from its second differences, and the frames' stamp jitter "
      "(the ground truth is read at the stamps) added to each edge's covariance (summary.json "
      "edge_chi2; an exact synthetic ground truth with exact stamps reads the same twice).\n\n",
      [](const TRunRecord* rec)
      {
        if (rec && !rec->ok)
          return std::string("FAILED");
        if (rec && rec->number("edge_chi2.median"))
          return optNum(rec->number("edge_chi2.median"), 1) + " / " +
                 optNum(rec->number("edge_chi2.with_ground_truth_noise.median"), 1);
        return std::string("—");
      });
}

void CTrajectoryTableWriter::renderTest2PerSequence(std::ostream& md, const TRecordList& t2) const
{
  renderPerSequenceTable(
      md, t2, "### Per sequence: ATE RMSE (m) / duration (s)\n\n",
      [](const TRunRecord* rec)
      {
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
        return oneLine(cell);
      });
}

void CTrajectoryTableWriter::renderPerSequenceTable(
    std::ostream& md, const TRecordList& t2, const std::string& heading,
    const std::function<std::string(const TRunRecord*)>& cellOf) const
{
  const auto feats = featuresOf(t2);
  md << heading << "| sequence | version |";
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
        md << " " << cellOf(findRun(t2, s, vk, f)) << " |";
      md << "\n";
    }
  md << "\n";
}

void CTrajectoryTableWriter::renderTest3(std::ostream& md, const TRecordList& t3) const
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

void CTrajectoryTableWriter::renderTest4(std::ostream& md, const TRecordList& t4) const
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
}  // namespace roislam::bench
