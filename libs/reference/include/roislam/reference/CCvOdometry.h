/* OpenCV's RGB-D odometries (opencv_rgbd: cv::rgbd::RgbdOdometry,
 * ICPOdometry, RgbdICPOdometry) run frame to frame, each frame against the
 * previous one, no keyframes, no loop closure: the reference our front end is
 * compared with in roi-bench (CCvOdometryApp, the cv-odometry app). The
 * odometries model a pinhole camera only, so a distorted camera's colour and
 * depth are undistorted first onto the same camera matrix (colour bilinear,
 * depth nearest), which gives them the same intrinsics our front end uses.
 *
 * ini section [CvOdometry] (TOptions):
 *   method           rgbd|icp|rgbdicp  rgbdicp  which cv::rgbd odometry
 *   min_depth        double >= 0       0     m  depths outside [min, max] are ignored
 *   max_depth        double > min      4     m
 *   max_depth_diff   double > 0        0.07  m  correspondence gate (OpenCV default)
 *   max_points_part  double in (0, 1]  0.07     share of pixels used (OpenCV default)
 *   undistort        bool              true     undistort when the camera has distortion
 * The defaults are OpenCV's. A bad value throws std::invalid_argument naming
 * the section and key.
 */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/img/TCamera.h>
#include <mrpt/poses/CPose3D.h>
#include <roislam/io/TRGBDFrame.h>

#include <memory>
#include <string>

namespace roislam::reference
{
class CCvOdometry
{
 public:
  struct TOptions : public mrpt::config::CLoadableOptions
  {
    std::string method = "rgbdicp";
    double min_depth = 0;          //!< m
    double max_depth = 4;          //!< m
    double max_depth_diff = 0.07;  //!< m
    double max_points_part = 0.07;
    bool undistort = true;

    /** Throws std::invalid_argument "[<section>] <key>: ..." on a bad value. */
    void validate(const std::string& section = "CvOdometry") const;
    void loadFromConfigFile(
        const mrpt::config::CConfigFileBase& cfg, const std::string& section) override;
    void saveToConfigFile(
        mrpt::config::CConfigFileBase& cfg, const std::string& section) const override;
  };

  /** One processed frame. */
  struct TStep
  {
    /** Pose of this frame's camera in the first frame's optical frame. */
    mrpt::poses::CPose3D pose;
    /** false: the odometry failed (OpenCV's own checks, e.g. more than 15 cm or
     *  15 deg per frame) and the pose was kept from the previous frame. */
    bool tracked = true;
    double ms = 0;  //!< time of this frame's odometry, undistortion included
  };

  /** Throws std::invalid_argument on invalid options or a camera without a
   *  positive focal length and size. */
  CCvOdometry(const TOptions& options, const mrpt::img::TCamera& camera);
  ~CCvOdometry();
  CCvOdometry(const CCvOdometry&) = delete;
  CCvOdometry& operator=(const CCvOdometry&) = delete;

  /** Tracks `frame` against the previous one (the first frame is the origin).
   *  Throws std::invalid_argument when the images do not match the camera. */
  TStep process(const io::TRGBDFrame& frame);

  /** OpenCV's class name of the method ("RgbdICPOdometry", ...). */
  static std::string className(const std::string& method);

  const TOptions& options() const { return m_options; }

 private:
  struct TImpl;
  TOptions m_options;
  std::unique_ptr<TImpl> m_impl;
};
}  // namespace roislam::reference
