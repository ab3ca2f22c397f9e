/* The cv-odometry application as a library class: runs CCvOdometry (OpenCV's
 * cv::rgbd odometry, frame to frame) over a frame source (TUM folder or
 * rawlog, the intrinsics resolved as every app does) and writes into the
 * output folder trajectory.txt (TUM, colour stamps, every frame) and
 * summary.json (frames, tracked / failed frames, ms_per_frame of the odometry
 * alone, wall_s, fps, ate_rmse, rpe_trans_rmse, rpe_rot_rmse_deg when the
 * sequence has ground truth, the method and camera). roi-bench runs it for
 * its reference rows; apps/cv-odometry only parses arguments.
 *
 * The ini (optional) is read from section [CvOdometry] (CCvOdometry.h); an
 * unknown key there is an error.
 */
#pragma once

#include <roislam/reference/CCvOdometry.h>

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace roislam::reference
{
class CCvOdometryApp
{
 public:
  struct TArguments
  {
    std::string input;      //!< TUM folder or .rawlog
    std::string outputDir;  //!< created when missing
    std::string camera = "auto";
    std::string iniFile;        //!< "" = defaults
    std::string method;         //!< "" = the ini's (or the default); overrides the ini
    std::size_t maxFrames = 0;  //!< 0 = all
    std::function<void(const std::string&)> progress;
  };

  struct TSummary
  {
    std::size_t frames = 0, trackedFrames = 0, failedFrames = 0;
    double msPerFrame = 0;  //!< mean time of the odometry per frame (decoding excluded)
    double wallS = 0, fps = 0;
    std::optional<double> ateRmse, rpeTransRmse, rpeRotRmseDeg;
    nlohmann::json json;  //!< what summary.json holds
  };

  /** Loads and validates the options; throws on a bad ini or argument. */
  explicit CCvOdometryApp(const TArguments& args);
  /** Runs and writes the outputs; throws std::runtime_error with one line
   *  naming the file on bad input or an unwritable output. */
  TSummary run() const;

 private:
  TArguments m_args;
  CCvOdometry::TOptions m_options;
};
}  // namespace roislam::reference
