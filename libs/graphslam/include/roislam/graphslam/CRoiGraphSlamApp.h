/* The roi-graphslam application: RGB-D graph SLAM over a TUM folder or a
 * rawlog with our deciders (CKeyframeNRD / CKeyframeERD / CKeyframeGSO on a
 * CNetworkOfPoses3DInf) inside MRPT's graph-SLAM engine (CSlamPipeline, the
 * same path as roi-graphslam-engine), configured by roi-graphslam's ini
 * ([FrontEnd], [GraphSlam], ...; MRPT's graph-SLAM sections are read too,
 * SlamIni.h) and the command line. While frame i is processed, frame i+1 is
 * decoded on a second thread. Outputs: CSlamRunner.h (the folder complete or
 * absent, a non-empty one refused unless `overwrite`). The colour camera's
 * rolling-shutter readout comes from the sensor description
 * (io::CFrameSource::sensor(), --camera): the run prints which description
 * it picked and why, and summary.json records it ("sensor"). An ini that
 * still sets [FrontEnd] rolling_shutter_ms (configs before the sensor
 * description) overrides the description's readout, and the run says so.
 * Called by apps/roi-graphslam and tests.
 */
#pragma once

#include <roislam/graphslam/CSlamContext.h>
#include <roislam/graphslam/CSlamObserver.h>
#include <roislam/graphslam/TSlamSummary.h>
#include <roislam/io/CFrameSource.h>

#include <functional>
#include <optional>
#include <string>

namespace roislam::graphslam
{
class CRoiGraphSlamApp
{
 public:
  struct TArguments
  {
    /** MRPT ini file; empty = defaults. */
    std::string iniFile;
    /** TUM folder or .rawlog. */
    std::string input;
    std::string outputDir;
    /** Command-line overrides of the ini. */
    std::optional<std::string> mode;     //!< [FrontEnd] mode
    std::optional<std::string> feature;  //!< [FeatureExtractor] feature_type
    std::optional<int> maxFeatures;      //!< [FeatureExtractor] max_features
    std::optional<bool> strictRoi;       //!< [FrontEnd] strict_roi
    bool snapshot = true;
    /** Replace an earlier output in outputDir (only our own files). */
    bool overwrite = false;
    /** Camera spec as io::resolveCamera (default auto). */
    std::string camera = "auto";
    /** Process at most this many frames (0 = all). */
    std::size_t maxFrames = 0;
    /** Progress lines (e.g. to stderr); may be empty. */
    std::function<void(const std::string&)> progress;
    /** Watches the run (the live view); not owned, may be null. Its
     *  stopRequested() ends the run early, the outputs still written. */
    CSlamObserver* observer = nullptr;
  };

  /** Headline figures (a subset of summary.json). */
  using TSummary = TSlamSummary;

  /** Loads the ini (strict keys) and applies the overrides; throws on a bad
   *  file, key or value (message names the file / section / key). */
  explicit CRoiGraphSlamApp(TArguments arguments);

  const CSlamContext::TConfig& config() const { return m_config; }
  /** TArguments::observer, set after construction (not owned, may be null). */
  void setObserver(CSlamObserver* observer) { m_args.observer = observer; }

  /** Runs the whole sequence and writes the outputs. Throws when the input
   *  cannot be read or the output folder is not writable. */
  TSummary run();

  /** "name: description" lines of the node ("node") or edge ("edge")
   *  registration deciders that can run, then those that cannot, with the
   *  reason (CRoislamOptionsChecker::describeRegistrars). */
  static std::string listRegistrars(const std::string& type);

 private:
  /** Prints the source's sensor description and takes its camera facts into
   *  the front end (applySensorFacts: the readout unless the ini set
   *  rolling_shutter_ms, the depth-noise model). */
  void applySensor(const io::CFrameSource& source);

  TArguments m_args;
  CSlamContext::TConfig m_config;
  /** [FrontEnd] rolling_shutter_ms was in the ini (it then overrides the sensor's). */
  bool m_iniReadout = false;
};
}  // namespace roislam::graphslam
