/* The Test 1 section of report.md (roi-landmarks, the ROI landmark pipeline
 * alone): landmarks / false positives / false negatives per sequence next
 * to the dissertation's, matches and speed per run, re-identification
 * precision / recall per extractor, and the hue-verified variant side by
 * side with the plain runs. Called by CReportWriter::render; private to
 * libs/bench.
 */
#pragma once

#include <roislam/bench/CDissertationReference.h>
#include <roislam/bench/TRunRecord.h>

#include <ostream>
#include <vector>

namespace roislam::bench
{
class CTest1TableWriter
{
 public:
  using TRecordList = std::vector<const TRunRecord*>;

  /** `reference` must outlive the writer. */
  explicit CTest1TableWriter(const CDissertationReference& reference);

  /** The section for the Test-1 records (plan order, not empty). */
  void render(std::ostream& md, const TRecordList& t1) const;

 private:
  void renderLandmarks(std::ostream& md, const TRecordList& t1) const;
  void renderMatches(std::ostream& md, const TRecordList& t1) const;
  void renderReidentification(std::ostream& md, const TRecordList& t1) const;
  /** Test 1 with and without the hue variant, side by side. */
  void renderHueVerification(std::ostream& md, const TRecordList& t1) const;

  const CDissertationReference& m_ref;
};
}  // namespace roislam::bench
