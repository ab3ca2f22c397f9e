/* Converts a TUM RGB-D benchmark folder into an MRPT rawlog of
 * CObservation3DRangeScan (the library side of the tum2rawlog app; also used
 * by tests and scripts).
 *
 * Output for --output DIR/NAME.rawlog:
 *  - DIR/NAME.rawlog: one observation per associated colour/depth pair,
 *    observation-only format, gz-compressed. sensorLabel "RGBD"; raw 16-bit
 *    TUM depth embedded as rangeImage with rangeUnits = 1/depth_scale
 *    (1/5000); cameraParams = cameraParamsIntensity = the intrinsics;
 *    relativePoseIntensityWRTDepth = "cameras coincide"; range_is_depth;
 *    timestamp = colour stamp; sensorPose = tumSensorPose() (robot frame = TUM
 *    optical frame, see ObservationConversion.h).
 *  - DIR/NAME_Images/<colour file name>: the colour PNGs, hard-linked from the
 *    dataset when possible, otherwise copied. Observations reference them by
 *    ABSOLUTE path, so rawlog-edit / RawLogViewer find them from any working
 *    directory despite MRPT 2.5.8's broken images-folder detection. (Our own
 *    reader also finds them after rawlog and folder are moved together.)
 *  - DIR/NAME.groundtruth.txt: copy of groundtruth.txt when present.
 *  - DIR/NAME.accelerometer.txt: copy of accelerometer.txt when present.
 * Everything is written under temporary names and renamed at the end; on any
 * error nothing is left behind. An existing NAME_Images folder is replaced.
 * Progress goes to the COutputLogger (console output disabled: the app prints
 * it to stderr through a callback).
 */
#pragma once

#include <mrpt/system/COutputLogger.h>
#include <roislam/io/CTumFrameSource.h>

#include <optional>
#include <string>

namespace roislam::io
{
class CTum2RawlogApp : public mrpt::system::COutputLogger
{
 public:
  struct TOptions
  {
    std::string input;              //!< TUM folder
    std::string output;             //!< .rawlog file
    std::string camera = "auto";    //!< as resolveCamera()
    int compressLevel = 1;          //!< gz level of the rawlog, 0..9
    CTumFrameSource::TOptions tum;  //!< association window, depth scale
  };

  struct TResult
  {
    std::size_t frames = 0;                    //!< observations written
    std::size_t skipped = 0;                   //!< colour frames without depth partner
    std::string rawlog;                        //!< absolute path of the rawlog
    std::string imagesDir;                     //!< absolute path of NAME_Images
    std::optional<std::string> groundTruth;    //!< copied ground truth, if any
    std::optional<std::string> accelerometer;  //!< copied accelerometer log, if any
    double seconds = 0;                        //!< wall time
  };

  explicit CTum2RawlogApp(const TOptions& options);
  /** Runs the conversion; throws std::runtime_error (one line, naming the
   *  file) on bad input or unwritable output, leaving no output behind. */
  TResult run();

 private:
  TOptions m_options;
};
}  // namespace roislam::io
