/* The paired end-to-end cost of several SLAM versions on one sequence: the
 * ratio to trust on a shared machine, because load hits every version alike.
 * One graphslam::CSlamPipeline per version (what roi-graphslam runs: decoding
 * and the ROI one frame ahead, front end, back end, final optimisation),
 * configured from the version's ini plus its overrides, each decoding its own
 * copy of the sequence, stepped in turn frame by frame with the order rotated
 * per frame. Each step plus the wait for its next frame is timed (wall clock
 * and process CPU, all threads), then the final optimisation; the front end's
 * own time (frames.csv frontend_ms: decoding excluded) is summed from the
 * records. The sensor's camera facts (readout unless the ini sets
 * rolling_shutter_ms, depth noise) are applied as roi-graphslam applies them,
 * so a version's ATE is the app's for the same settings.
 *
 * Called by roi-bench (CBenchApp: Test 2's speed table) and by
 * roislam-stage-bench --paired-slam-passes (tests/benchmark). Every pipeline is
 * held at once: memory grows with the number of versions.
 */
#pragma once

#include <roislam/bench/TPairedCost.h>
#include <roislam/bench/TVariant.h>
#include <roislam/features/TFeatureSet.h>

#include <cstddef>
#include <string>
#include <vector>

namespace roislam::bench
{
class CPairedSlamCost
{
 public:
  /** A version: its key (report and ratios), its config file and the ini
   *  overrides applied to that file's text (TVariant, applyIniOverrides). */
  struct TVersion
  {
    std::string key;
    std::string label;  //!< "" = the key
    std::string iniFile;
    std::vector<TIniOverride> overrides;
  };

  struct TOptions
  {
    std::string sequence;  //!< TUM folder or rawlog (io::CFrameSource::open)
    /** The versions, the reference of the ratios (traditional) first. */
    std::vector<TVersion> versions;
    features::EFeatureType feature = features::EFeatureType::SURF;
    /** Replaces the ini's, as roi-graphslam --max-features; < 0 keeps it. */
    int max_features = 600;
    int passes = 1;              //!< >= 1; each pass builds fresh pipelines
    std::size_t max_frames = 0;  //!< frames per pass, 0 = the whole sequence
  };

  /** Checks the options and loads every version's config: throws
   *  std::invalid_argument on bad options, std::runtime_error "ini <file>: no
   *  such file" or the config's own error (naming the file and key). */
  explicit CPairedSlamCost(TOptions options);

  /** Runs the passes. The result has sequencePath, feature, maxFeatures,
   *  passes, maxFrames and one entry per version, in order; figures are
   *  per frame over all passes, frames and lost frames per pass, ATE from the
   *  last pass (none without ground truth or when too short to evaluate).
   *  Errors of a pipeline propagate, headed by the version's key. */
  TPairedCost run() const;

  const TOptions& options() const { return m_options; }

 private:
  TOptions m_options;
};
}  // namespace roislam::bench
