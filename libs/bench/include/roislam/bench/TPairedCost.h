/* The figures of one paired cost measurement (CPairedSlamCost): one sequence,
 * one extractor, several versions stepped in turn frame by frame. roi-bench
 * writes one per Test-2 sequence x extractor into <output>/speed.json
 * (savePairedCosts) and CReportWriter renders the speed table from that file
 * (loadPairedCosts).
 *
 * speed.json: {"format": "roi-bench paired cost 1", "runs": [<toJson()>...]}.
 */
#pragma once

#include <roislam/bench/TVariant.h>

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace roislam::bench
{
struct TPairedCost
{
  /** One version's figures; the ratios are to the first version's (traditional). */
  struct TVersion
  {
    std::string key;    //!< e.g. "traditional", "roi_big/flow" (TBenchRun::versionKey)
    std::string label;  //!< shown in the report ("" = the key)
    std::string iniFile;
    std::vector<TIniOverride> overrides;
    std::size_t frames = 0;         //!< frames of one pass
    std::size_t lostFrames = 0;     //!< of one pass (strict ROI only)
    double wallMsPerFrame = 0;      //!< step + wait for the next frame, final optimisation
    double cpuMsPerFrame = 0;       //!< process CPU (all threads) over the same spans
    double frontEndMsPerFrame = 0;  //!< the front end's own time, decoding excluded
    double fps = 0;                 //!< 1000 / wallMsPerFrame
    std::optional<double> ateRmse;  //!< m, last pass, when the sequence has ground truth
    double wallRatio = 1;           //!< wall(this) / wall(first)
    double cpuRatio = 1;            //!< cpu(this) / cpu(first)
    double frontEndRatio = 1;       //!< front end(this) / front end(first)
  };

  std::string sequence;      //!< name (roi-bench's TSequence::name)
  std::string sequencePath;  //!< TUM folder or rawlog
  std::string feature;       //!< surf | sift | orb
  int maxFeatures = 0;
  int passes = 0;
  std::size_t maxFrames = 0;  //!< 0 = whole sequence
  std::vector<TVersion> versions;
  /** Versions not measured, and why (e.g. the strict ROI lost frames). */
  std::vector<std::pair<std::string, std::string>> leftOut;
  /** Non-empty when the measurement failed: no figures (the versions, if
   *  any, are those it tried). */
  std::string error;

  bool ok() const { return error.empty() && !versions.empty(); }
  nlohmann::json toJson() const;
  /** Throws std::runtime_error on a malformed entry. */
  static TPairedCost fromJson(const nlohmann::json& j);
};

/** Reads speed.json; throws std::runtime_error "<file>: ..." (one line) when
 *  it is missing, not JSON or not in the format above. */
std::vector<TPairedCost> loadPairedCosts(const std::string& file);
/** Writes speed.json atomically. */
void savePairedCosts(const std::vector<TPairedCost>& costs, const std::string& file);
}  // namespace roislam::bench
