/* The trajectory sections of report.md: Test 2 (roi-graphslam, mean ± std
 * of ATE / RPE and durations per version x extractor next to the
 * dissertation's, then per sequence, and how honest the graph's edges
 * are: their chi² against ground truth), Test 3 (reduced features) and Test 4
 * (EKF-SLAM vs odometry alone vs graph SLAM). Called by
 * CReportWriter::render; private to libs/bench.
 */
#pragma once

#include <roislam/bench/CDissertationReference.h>
#include <roislam/bench/TRunRecord.h>

#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace roislam::bench
{
class CTrajectoryTableWriter
{
 public:
  using TRecordList = std::vector<const TRunRecord*>;

  /** `reference` must outlive the writer. */
  explicit CTrajectoryTableWriter(const CDissertationReference& reference);

  /** Each for its test's records (plan order, not empty). */
  void renderTest2(std::ostream& md, const TRecordList& t2) const;
  void renderTest3(std::ostream& md, const TRecordList& t3) const;
  /** Test 4: EKF-SLAM, odometry alone and graph SLAM per sequence and extractor. */
  void renderTest4(std::ostream& md, const TRecordList& t4) const;

 private:
  using TGetter = std::function<std::optional<double>(const TRunRecord&)>;
  /** The dissertation's cell for (mode, feature), "—" when it has none. */
  using TReference = std::function<std::string(const std::string&, const std::string&)>;

  /** One metric: a row per version, per extractor our cell and ref's. */
  void renderVersionTable(
      std::ostream& md, const TRecordList& t2, const std::string& title,
      const std::string& refLabel, int decimals, const TGetter& get, const TReference& ref) const;
  void renderTest2PerSequence(std::ostream& md, const TRecordList& t2) const;
  /** Per sequence, the graph edges' chi² against ground truth (median,
   *  and with the ground truth's own noise; EdgeChi2.h), when any run has it. */
  void renderTest2EdgeChi2(std::ostream& md, const TRecordList& t2) const;
  /** A table under `heading`: a row per sequence and version, a column per
   *  extractor, each cell cellOf(the run, or null when there is none). */
  void renderPerSequenceTable(
      std::ostream& md, const TRecordList& t2, const std::string& heading,
      const std::function<std::string(const TRunRecord*)>& cellOf) const;

  const CDissertationReference& m_ref;
};
}  // namespace roislam::bench
