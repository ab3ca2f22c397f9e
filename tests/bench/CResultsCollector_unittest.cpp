/* results.csv: every scalar of a run's summary.json becomes a column, at
 * any depth ("object.key..."), so that nested figures such as the edges'
 * chi² with the ground truth's noise can be compared across runs. */
#include <gtest/gtest.h>
#include <roislam/bench/CResultsCollector.h>

#include <sstream>
#include <string>
#include <vector>

using roislam::bench::CResultsCollector;
using roislam::bench::TRunRecord;

namespace
{
std::vector<std::string> splitLine(const std::string& line)
{
  std::vector<std::string> out;
  std::stringstream ss(line);
  for (std::string f; std::getline(ss, f, ',');)
    out.push_back(f);
  if (!line.empty() && line.back() == ',')
    out.emplace_back();  // the last field is empty (getline drops it)
  return out;
}
}  // namespace

TEST(CResultsCollector, NestedSummaryFieldsBecomeDottedColumns)
{
  TRunRecord a;
  a.run.id = "a";
  a.ok = true;
  a.summary = {
      {"ate_rmse", 0.01},
      {"kf_slam", {{"ate_rmse", 0.02}}},
      {"edge_chi2",
       {{"median", 300.0},
        {"direction", {1, 2, 3, 4, 5, 6}},
        {"with_ground_truth_noise", {{"median", 25.5}, {"direction", {1, 1, 1, 1, 1, 1}}}},
        {"by_kind", {{"loop", {{"edges", 7}}}}}}}};
  TRunRecord b;
  b.run.id = "b";
  b.ok = true;
  b.summary = {{"ate_rmse", 0.03}, {"edge_chi2", {{"median", 12.0}}}};
  const std::string csv = CResultsCollector::toCsv({a, b});
  std::stringstream lines(csv);
  std::string header, rowA, rowB;
  std::getline(lines, header);
  std::getline(lines, rowA);
  std::getline(lines, rowB);
  const auto h = splitLine(header), ra = splitLine(rowA), rb = splitLine(rowB);
  ASSERT_EQ(h.size(), ra.size());
  ASSERT_EQ(h.size(), rb.size());
  const auto column = [&h](const std::string& key) -> std::ptrdiff_t
  {
    for (std::size_t i = 0; i < h.size(); ++i)
      if (h[i] == key)
        return static_cast<std::ptrdiff_t>(i);
    return -1;
  };
  for (const char* key :
       {"kf_slam.ate_rmse", "edge_chi2.median", "edge_chi2.with_ground_truth_noise.median",
        "edge_chi2.by_kind.loop.edges"})
    ASSERT_GE(column(key), 0) << key << " missing from " << header;
  // Arrays have no column; an object is not a column of its own.
  EXPECT_LT(column("edge_chi2.direction"), 0);
  EXPECT_LT(column("edge_chi2.with_ground_truth_noise.direction"), 0);
  EXPECT_LT(column("edge_chi2.with_ground_truth_noise"), 0);
  const auto at = [&](const std::vector<std::string>& row, const char* key)
  { return row[static_cast<std::size_t>(column(key))]; };
  EXPECT_DOUBLE_EQ(std::stod(at(ra, "edge_chi2.with_ground_truth_noise.median")), 25.5);
  EXPECT_EQ(std::stoi(at(ra, "edge_chi2.by_kind.loop.edges")), 7);
  EXPECT_DOUBLE_EQ(std::stod(at(rb, "edge_chi2.median")), 12.0);
  // A run without the field leaves its cell empty.
  EXPECT_EQ(at(rb, "edge_chi2.with_ground_truth_noise.median"), "");
}
