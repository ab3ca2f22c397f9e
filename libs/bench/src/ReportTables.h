/* What the tables of report.md share: number formatting, the order of
 * versions and extractors, a per-extractor table header, and one cell
 * aggregated over sequences. Used by CReportWriter and its section writers
 * (CTest1TableWriter, CTrajectoryTableWriter, ReferenceTable,
 * CSpeedTableWriter). Private to libs/bench.
 */
#pragma once

#include <roislam/bench/TRunRecord.h>

#include <algorithm>
#include <cstddef>
#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace roislam::bench::report
{
/** Extractors in the dissertation's order. */
extern const std::vector<std::string> kFeatures;

/** Fixed-point text of v with `decimals` decimals. */
std::string num(double v, int decimals);

/** num(*v, decimals), "n/a" when there is no value. */
std::string optNum(const std::optional<double>& v, int decimals);

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
std::vector<std::string> featuresOf(const std::vector<const TRunRecord*>& recs);

/** Version keys of records ordered traditional, small ROI, big ROI (plan order within). */
std::vector<std::string> versionKeys(const std::vector<const TRunRecord*>& recs);

/** Table header "| first |" + per extractor " F | F <refLabel> |" and its rule. */
void featureHeader(
    std::ostream& md, const std::string& first, const std::vector<std::string>& feats,
    const std::string& refLabel);

/** Report label of a version key, from the first record of that version
 *  (the key itself when there is none). */
std::string labelOf(const std::vector<const TRunRecord*>& recs, const std::string& vk);

/** Aggregated figure over sequences for one table cell. */
struct TCell
{
  std::vector<double> values;
  std::size_t failed = 0, total = 0, missingValue = 0;
};

using TGetter = std::function<std::optional<double>(const TRunRecord&)>;

/** The figure `get` of the runs of one version and extractor. */
TCell cellFor(
    const std::vector<const TRunRecord*>& recs, const std::string& vk, const std::string& f,
    const TGetter& get);

/** "mean ± std (n=.., k failed)", "FAILED (k/n)", "n/a" or "—" (no run). */
std::string renderCell(const TCell& c, int decimals, bool withStd);

/** The summary figure `key` of a run. */
TGetter getter(const std::string& key);

/** Wall time of a run, s: the app's own figure when it has one. */
double durationOf(const TRunRecord& r);

/** s on one table line: '|' and newlines replaced by spaces. */
std::string oneLine(std::string s);
}  // namespace roislam::bench::report
