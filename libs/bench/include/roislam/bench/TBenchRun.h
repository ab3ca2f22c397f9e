/* One planned run of roi-bench: which test, sequence, app, mode, extractor,
 * feature cap and variant, where its results go and the exact command line.
 * Produced by CExperimentPlan, executed by CBenchRunner, stored in run.json.
 */
#pragma once

#include <roislam/bench/TVariant.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace roislam::bench
{
struct TBenchRun
{
  std::string id;            //!< unique, file-name safe, e.g. t2-seq-roi_big-surf-600-strict
  int test = 0;              //!< 1..4, or 0: a reference row (cv-odometry)
  std::string sequence;      //!< TSequence::name
  std::string sequencePath;  //!< input folder
  std::string app;           //!< roi-landmarks | roi-graphslam | cv-odometry
  std::string mode;     //!< "" (test 1) | traditional | roi_small | roi_big | cv_<method> (test 0)
  std::string feature;  //!< surf | sift | orb ("" for reference rows)
  int maxFeatures = 0;  //!< 0 = the app's default (not passed)
  std::string variant;  //!< "" = none (test 1, traditional)
  std::string variantLabel;
  std::string baseIni;  //!< config file of the mode
  std::string iniFile;  //!< file passed to --ini (derived from baseIni for a variant)
  std::vector<TIniOverride> iniOverrides;  //!< baseIni + these = iniFile
  std::string runDir;                      //!< <output>/runs/<id>: run.json, logs
  std::string appOutputDir;                //!< <runDir>/output: the app's --output-dir
  std::vector<std::string> argv;           //!< exact command, argv[0] = executable

  /** "traditional", "roi_small/strict", ... : version and variant as one key. */
  std::string versionKey() const { return variant.empty() ? mode : mode + "/" + variant; }
  nlohmann::json toJson() const;
  /** Throws std::runtime_error when a required field is missing. */
  static TBenchRun fromJson(const nlohmann::json& j);
};
}  // namespace roislam::bench
