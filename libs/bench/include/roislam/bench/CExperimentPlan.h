/* The experiment plan of roi-bench: the runs of Tests 1-3 (the dissertation's
 * evaluation, /work/shared/MISSION.md) and the optional Test 4 for a set of
 * sequences, each with its folder and exact command line. Test 1:
 * roi-landmarks per sequence x feature, once plain and once per Test-1
 * variant (default "hue": [RoiDetector] verify_hue = true). Test 2:
 * roi-graphslam per sequence x mode x feature, capped features. Test 3: the
 * test-3 feature capped low, traditional vs big ROI. ROI modes of Tests 2-3
 * run once per variant (strict = dissertation, fallback = ours). Test 4 (not
 * in the default list): EKF-SLAM on ROI landmarks, per sequence x feature
 * roi-landmarks --kf-slam (its summary also holds the odometry alone) and
 * roi-graphslam with the same front end (roi_big.ini, whose [FrontEnd]
 * [KfSlam] front_end_ini names), for the three-way comparison.
 *
 * ini section [Bench] (TOptions):
 *   tests               list of 1..4    1,2,3          tests to plan
 *   features            list            surf,sift,orb  extractors
 *   modes               list            traditional,roi_small,roi_big (test 2)
 *   test1_max_features  int >= 0        0              0 = app default (not passed)
 *   test2_max_features  int > 0         600
 *   test3_max_features  int > 0         50
 *   test3_feature       string          surf
 *   test3_modes         list            traditional,roi_big
 *   snapshots           bool            false          false passes --no-snapshot
 * Variants (variants: Tests 2-3; test1_variants: Test 1) are set in code or
 * by roi-bench --variant / --no-default-variants (not from the ini).
 */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <roislam/bench/TBenchRun.h>
#include <roislam/bench/TSequence.h>
#include <roislam/bench/TVariant.h>

#include <map>
#include <set>
#include <string>
#include <vector>

namespace roislam::bench
{
class CExperimentPlan
{
 public:
  struct TOptions : public mrpt::config::CLoadableOptions
  {
    std::set<int> tests{1, 2, 3};
    std::vector<std::string> features{"surf", "sift", "orb"};
    std::vector<std::string> modes{"traditional", "roi_small", "roi_big"};
    int test1_max_features = 0;
    int test2_max_features = 600;
    int test3_max_features = 50;
    std::string test3_feature = "surf";
    std::vector<std::string> test3_modes{"traditional", "roi_big"};
    bool snapshots = false;
    std::vector<TVariant> variants = defaultVariants();
    std::vector<TVariant> test1_variants = defaultTest1Variants();

    /** Throws std::invalid_argument "[<section>] <key>: ..." on a bad value. */
    void validate(const std::string& section = "Bench") const;
    void loadFromConfigFile(
        const mrpt::config::CConfigFileBase& cfg, const std::string& section) override;
    void saveToConfigFile(
        mrpt::config::CConfigFileBase& cfg, const std::string& section) const override;
  };

  /** Where things are: app name -> executable, the config folder, the output. */
  struct TLocations
  {
    std::map<std::string, std::string> executables;  //!< missing app -> its bare name
    std::string configDir;
    std::string outputDir;
  };

  CExperimentPlan(const TOptions& options, const TLocations& locations);

  /** Every run, in the order test 1, 2, 3; sequence; mode; feature; variant. */
  std::vector<TBenchRun> build(const std::vector<TSequence>& sequences) const;

  /** Writes each distinct derived ini file (variant configs) of `runs`, from
   *  its base ini. Throws std::runtime_error naming a missing base file. */
  static void writeVariantConfigs(const std::vector<TBenchRun>& runs);

  /** Each dir is a sequence (has rgb.txt) or a folder whose subfolders are;
   *  names are made unique. Throws std::runtime_error naming a dir without
   *  any sequence. */
  static std::vector<TSequence> discoverSequences(const std::vector<std::string>& dirs);

  /** Parses "1,2,3,4" into a set; throws std::invalid_argument on other values. */
  static std::set<int> parseTests(const std::string& text);

  const TOptions& options() const { return m_options; }

 private:
  TOptions m_options;
  TLocations m_locations;
  TBenchRun makeRun(
      int test, const TSequence& seq, const std::string& mode, const std::string& feature,
      int maxFeatures, const TVariant* variant) const;
  /** Test 4: kind "kf_slam" (roi-landmarks --kf-slam) or "graph_slam"
   *  (roi-graphslam, big ROI, the EKF's front end). */
  TBenchRun makeTest4Run(
      const TSequence& seq, const std::string& kind, const std::string& feature) const;
  /** The folder, output and executable of a run whose id is set. */
  void placeRun(TBenchRun& r) const;
};
}  // namespace roislam::bench
