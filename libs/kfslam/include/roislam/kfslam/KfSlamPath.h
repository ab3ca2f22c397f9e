/* From the filter's frame to ours, and kf-slam's own files: the robot path
 * of a CKfSlamFilter run as a TUM camera trajectory, the reference landmark
 * positions for kf-slam's error report, and the robot_pose files of the
 * stock kf-slam app. Used by CKfSlamSession and the tests.
 *
 * The filter's frame is the robot's at its first landmark step k0 (MRPT
 * holds the robot at the origin until then, CKfSlamFilter.h). A step k >= k0
 * is placed at O(k0) (+) E(k), O the odometry's robot pose, E the filter's;
 * a step before k0, which the filter did not move, takes the odometry's
 * pose O(k). Both trajectories are then in the odometry's world, so they
 * compare directly.
 */
#pragma once

#include <mrpt/math/TPoint3D.h>
#include <mrpt/poses/CPose3D.h>
#include <roislam/io/TumTrajectory.h>
#include <roislam/kfslam/CKfSlamFilter.h>
#include <roislam/kfslam/COdometryIncrements.h>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace roislam::kfslam
{
/** The run's robot poses in the odometry's world (rule above); odometry:
 *  the odometry's robot pose of each step. Throws std::invalid_argument when
 *  the sizes differ. */
std::vector<mrpt::poses::CPose3D> worldRobotPath(
    const TKfSlamRun& run, const std::vector<mrpt::poses::CPose3D>& odometry);

/** Robot poses as a TUM trajectory of optical camera poses. */
io::TTrajectory cameraTrajectory(
    const std::vector<mrpt::poses::CPose3D>& robotPath, const std::vector<double>& stamps,
    const COdometryIncrements& frames);

/** A landmark's first sighting: the frame's stamp and the point in the
 *  optical camera frame. */
struct TFirstSight
{
  double timestamp = 0;
  mrpt::math::TPoint3D optical;
};

/** Reference landmark positions in the filter's frame from ground truth: the
 *  first-sight point carried into the world by the ground-truth camera pose
 *  of its frame, then into the filter's frame (the ground-truth robot pose at
 *  the first landmark step, stamp k0Stamp). Landmarks whose frame has no
 *  ground-truth pose are left out. gt sorted by stamp. */
std::map<int64_t, mrpt::math::TPoint3D> referenceLandmarks(
    const std::map<int64_t, TFirstSight>& firstSights, const io::TTrajectory& gt, double k0Stamp,
    const COdometryIncrements& frames);

/** Mean distance between the map's landmarks and their references (the
 *  figure kf-slam reports as "Mean Error"); nullopt when none is shared. */
std::optional<double> meanLandmarkError(
    const std::map<int64_t, mrpt::math::TPoint3D>& map,
    const std::map<int64_t, mrpt::math::TPoint3D>& reference);

/** Writes references in kf-slam's ground_truth_file layout: one row per
 *  landmark "x y z 0 0 0 ID" (columns 0-2 and 6 are read). */
void saveKfSlamLandmarks(
    const std::string& file, const std::map<int64_t, mrpt::math::TPoint3D>& landmarks);

/** kf-slam's robot_pose_NNNNN.txt files of a folder (x y z qr qx qy qz, one
 *  number per line), in step order. Throws std::runtime_error naming a file
 *  that is malformed, or the folder when it has none. */
std::vector<mrpt::poses::CPose3D> loadKfSlamRobotPoses(const std::string& dir);
}  // namespace roislam::kfslam
