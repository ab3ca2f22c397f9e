/* The roi-graphslam-engine application: MRPT's graph-SLAM engine
 * (CGraphSlamEngine<CNetworkOfPoses3DInf>, CRgbdGraphSlamEngine) with the
 * command line of MRPT's graphslam-engine, headless: the node and edge
 * registration deciders and the optimiser chosen by name (ours by default,
 * MRPT's where they work in 3-D, CRoislamOptionsChecker), their parameters
 * read by their loadParams() from the ini (MRPT's sections,
 * config/graphslam-engine.ini, or roi-graphslam's, SlamIni.h) and printed
 * with printParams() before the run; ground truth from -g (TUM format, as
 * tum2rawlog writes NAME.groundtruth.txt) for ATE / RPE. Same outputs as
 * roi-graphslam (CSlamRunner.h), through the same pipeline (CSlamPipeline).
 * The camera facts (rolling-shutter readout, depth-noise model) come from
 * the sensor description as in roi-graphslam (--camera, default auto: the
 * rawlog's or folder's camera.ini, else the observations' intrinsics and a
 * preset; SensorFacts.h), not from the ini: the run prints which description
 * it picked and summary.json records it ("sensor"). An ini that still sets
 * rolling_shutter_ms overrides the description's readout, and the run says
 * so.
 * Called by apps/roi-graphslam-engine and tests.
 */
#pragma once

#include <roislam/graphslam/CSlamObserver.h>
#include <roislam/graphslam/TSlamDeciders.h>
#include <roislam/graphslam/TSlamSummary.h>
#include <roislam/io/CFrameSource.h>

#include <functional>
#include <memory>
#include <optional>
#include <string>

namespace roislam::graphslam
{
class CRoiGraphSlamEngineApp
{
 public:
  /** graphslam-engine's options (and --output-dir, --no-snapshot, --overwrite). */
  struct TArguments
  {
    std::string iniFile;                     //!< -i/--ini-file (required)
    std::string rawlog;                      //!< -r/--rawlog (required; a TUM folder also works)
    std::optional<std::string> groundTruth;  //!< -g/--ground-truth (TUM format)
    TSlamDeciders::TNames deciders;          //!< -n/--node-reg, -e/--edge-reg, -o/--optimizer
    bool twoD = false;                       //!< --2d: refused (our deciders build 3-D graphs)
    bool threeD = false;                     //!< --3d: the default
    bool disableVisuals = false;             //!< --disable-visuals: always headless
    std::string outputDir = "graphslam_results";  //!< --output-dir
    bool snapshot = true;                         //!< no --no-snapshot
    /** --camera: camera spec as io::resolveCamera (default auto). */
    std::string camera = "auto";
    /** --overwrite: replace an earlier output of ours in outputDir. */
    bool overwrite = false;
    /** Progress lines (e.g. to stderr); may be empty. */
    std::function<void(const std::string&)> progress;
    /** Told every frame and optimisation (e.g. the live view); not owned,
     *  may be null; its stopRequested() ends the run early, outputs written. */
    CSlamObserver* observer = nullptr;
  };

  /** Checks the arguments before any work: --2d (with a note on what to
   *  use), the deciders' names (unknown, 2-D only or not working here:
   *  CRoislamOptionsChecker::refusal), the ini, rawlog and ground-truth files
   *  (missing or malformed ground truth), and MRPT options that would crash
   *  (CLevMarqGSO with optimization_on_second_thread); opens the rawlog.
   *  Throws a one-line std::exception naming the option, file or key. */
  explicit CRoiGraphSlamEngineApp(TArguments arguments);

  /** Runs the engine over the whole rawlog and writes the outputs; prints
   *  the engine's and the deciders' parameters (printParams()) to stdout
   *  first. Call once. */
  TSlamSummary run();

  /** TArguments::observer, set after construction (not owned, may be null). */
  void setObserver(CSlamObserver* observer) { m_args.observer = observer; }

  /** --list-node-regs / --list-edge-regs / --list-regs / --list-optimizers:
   *  "node", "edge", "all" or "optimizer". */
  static std::string list(const std::string& what);

 private:
  TArguments m_args;
  std::unique_ptr<io::CFrameSource> m_source;
  /** The ini sets rolling_shutter_ms (it then overrides the sensor's). */
  bool m_iniReadout = false;
};
}  // namespace roislam::graphslam
