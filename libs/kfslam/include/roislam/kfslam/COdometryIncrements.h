/* The front end's odometry as the robot motion of each frame, with its
 * covariance: the actions (CActionRobotMovement3D) of the kf-slam rawlog.
 * Called by CKfSlamSession once per frame, in order.
 *
 * Frames. The front end's poses are optical camera poses (x right, y down,
 * z forward). The robot frame is the one the landmark observations'
 * sensorLocationOnRobot S refers to (S = pose of MRPT's camera frame on the
 * robot); the optical frame sits on the robot at T = S (+) tumSensorPose()^-1,
 * so robot = camera (+) T^-1 and a camera motion D is the robot motion
 * T (+) D (+) T^-1. With the default S (tumSensorPose) T is the identity and
 * the robot is the optical camera.
 *
 * Noise (TKfSlamOptions odometry_covariance). Each frame is registered
 * against a keyframe (pose = keyframe (+) r, r with the front end's
 * information). Two consecutive frames against the same keyframe move by
 * r_prev^-1 (+) r, whose covariance MRPT composes from both registrations';
 * a frame measured from the previous frame itself (it became the keyframe)
 * moves by r. The per-frame sigmas are added on the diagonal for what the
 * front end's reprojection Hessian does not model. Consecutive motions that
 * share a registration are correlated and the filter treats them as
 * independent, so over the frames between two keyframes it over-estimates
 * the drift; the drift of frame-to-keyframe odometry is made at keyframe
 * changes, which this counts once.
 */
#pragma once

#include <mrpt/poses/CPose3D.h>
#include <mrpt/poses/CPose3DPDFGaussian.h>
#include <roislam/frontend/TFrameResult.h>
#include <roislam/kfslam/TKfSlamOptions.h>

#include <optional>

namespace roislam::kfslam
{
class COdometryIncrements
{
 public:
  /** sensorPose: S above (sensorLocationOnRobot of the observations). */
  COdometryIncrements(const TKfSlamOptions& options, const mrpt::poses::CPose3D& sensorPose);

  /** The robot's motion since the previous frame's result (the first frame:
   *  identity with zero covariance); lost frames move by the identity with
   *  the weak covariance. */
  mrpt::poses::CPose3DPDFGaussian next(const frontend::TFrameResult& result);

  /** Robot pose of an optical camera pose, and back. */
  mrpt::poses::CPose3D robotPose(const mrpt::poses::CPose3D& camera) const;
  mrpt::poses::CPose3D cameraPose(const mrpt::poses::CPose3D& robot) const;

 private:
  /** The frame's own registration r with its covariance (weak when the
   *  front end gave no usable information). */
  mrpt::poses::CPose3DPDFGaussian registration(const frontend::TFrameResult& r) const;
  /** Covariance of the camera motion from prev to r. */
  mrpt::math::CMatrixDouble66 motionCovariance(const frontend::TFrameResult& r) const;
  mrpt::math::CMatrixDouble66 diagonal(double sigmaM, double sigmaDeg) const;

  TKfSlamOptions m_options;
  /** T above: the optical camera frame on the robot. */
  mrpt::poses::CPose3D m_opticalOnRobot;
  /** The last frame with a pose. */
  std::optional<frontend::TFrameResult> m_previous;
};
}  // namespace roislam::kfslam
