/* Options of roi-landmarks --kf-slam (CKfSlamSession): which kf-slam
 * configuration and front end to use, and the odometry's noise model.
 *
 * ini section [KfSlam] (in roi-landmarks' ini, config/roi_landmarks.ini):
 *  - kf_slam_ini          path (default kf-slam-roi.ini): MRPT kf-slam
 *                         configuration ([MappingApplication],
 *                         [RangeBearingKFSLAM], [RangeBearingKFSLAM_KalmanFilter];
 *                         config/kf-slam-roi.ini documents them). A relative
 *                         path is relative to the folder of the ini that
 *                         names it.
 *  - front_end_ini        path (default "": CRgbdOdometry's defaults): the
 *                         front end whose odometry makes the actions, read
 *                         from that file's [FrontEnd] and its sub-sections
 *                         (e.g. roi_big.ini, as roi-graphslam reads it);
 *                         relative as above. roi-landmarks' --feature and
 *                         --max-features apply to it too.
 *  - odometry_covariance  frontend|fixed (default frontend): the covariance
 *                         of each frame's motion. frontend: from the front
 *                         end's information of the frame's registration (and
 *                         of the previous frame's, when both were measured
 *                         against the same keyframe), plus the two sigmas
 *                         below in quadrature; fixed: the two sigmas alone
 *  - odometry_sigma_m     [m] >= 0 (default 0.002): per frame, on each axis
 *  - odometry_sigma_deg   [deg] >= 0 (default 0.1): per frame, on each angle
 *                         (at least one of the two > 0 with fixed)
 *  - weak_sigma_m, weak_sigma_deg  [m] > 0, [deg] > 0 (default 0.05, 5):
 *                         frames the front end extrapolated (constant
 *                         velocity) or lost, and registrations whose
 *                         information is singular
 * A bad value throws std::invalid_argument "[KfSlam] key: why".
 */
#pragma once

#include <mrpt/config/CLoadableOptions.h>

#include <string>

namespace roislam::kfslam
{
struct TKfSlamOptions : public mrpt::config::CLoadableOptions
{
  std::string kf_slam_ini = "kf-slam-roi.ini";
  std::string front_end_ini;
  std::string odometry_covariance = "frontend";
  double odometry_sigma_m = 0.002;
  double odometry_sigma_deg = 0.1;
  double weak_sigma_m = 0.05;
  double weak_sigma_deg = 5;

  void loadFromConfigFile(
      const mrpt::config::CConfigFileBase& source, const std::string& section) override;
  void saveToConfigFile(
      mrpt::config::CConfigFileBase& target, const std::string& section) const override;
  /** Throws std::invalid_argument "[KfSlam] key: why". */
  void validate(const std::string& section = "KfSlam") const;
};
}  // namespace roislam::kfslam
