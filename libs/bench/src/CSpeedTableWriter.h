/* The speed section of report.md: Test 2's versions per extractor, from the
 * paired measurement (roi-bench's speed.json, CPairedSlamCost) when there is
 * one, else from the Test-2 runs' own summaries. Called by
 * CReportWriter::render; private to libs/bench.
 */
#pragma once

#include <roislam/bench/TPairedCost.h>
#include <roislam/bench/TRunRecord.h>

#include <ostream>
#include <string>
#include <vector>

namespace roislam::bench
{
class CSpeedTableWriter
{
 public:
  using TRecordList = std::vector<const TRunRecord*>;

  /** `paired`: the entries of speed.json; empty = no paired measurement. */
  explicit CSpeedTableWriter(std::vector<TPairedCost> paired);

  /** The section for the Test-2 records (plan order): the paired table when
   *  there are paired entries, else the single runs' table. */
  void render(std::ostream& md, const TRecordList& t2) const;

 private:
  void renderPaired(std::ostream& md, const TRecordList& t2) const;
  /** Versions in the report's order (traditional, small, big; plan order
   *  within), then any only the paired file knows. */
  std::vector<std::string> pairedVersionKeys(const TRecordList& t2) const;
  /** Extractors of the paired entries, SURF, SIFT, ORB first. */
  std::vector<std::string> pairedFeatures() const;
  /** One version and extractor over the sequences; nothing when no
   *  successful paired entry has that version. */
  void renderPairedRow(
      std::ostream& md, const TRecordList& t2, const std::string& vk, const std::string& f) const;
  /** Failed measurements and left-out versions, one line each. */
  void renderPairedNotes(std::ostream& md) const;

  void renderUnpaired(std::ostream& md, const TRecordList& t2) const;
  void renderUnpairedRow(
      std::ostream& md, const TRecordList& t2, const std::string& vk, const std::string& f) const;

  std::vector<TPairedCost> m_paired;
};
}  // namespace roislam::bench
