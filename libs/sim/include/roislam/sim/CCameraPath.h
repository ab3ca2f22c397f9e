/* Smooth closed 6-DoF camera path for CRgbdSimulator: a horizontal loop with a
 * vertical bob, yaw sweeping towards the loop's centre, pitch and roll wobble.
 * Every component is periodic over the sequence, so the last frame returns to
 * the first pose (a loop closure). Amplitudes are scaled down when needed so
 * the linear and angular speeds stay within handheld-Kinect limits.
 */
#pragma once

#include <mrpt/poses/CPose3D.h>

namespace roislam::sim
{
class CCameraPath
{
 public:
  struct TParams
  {
    /** Body pose (x forward, y left, z up) at the start and centre of the wobble. */
    double x = 0.1, y = 0.0, z = 1.35;              //!< metres
    double yawDeg = 0, pitchDeg = 17, rollDeg = 0;  //!< pitch > 0 looks down
    double translationAmplitude = 0.3;              //!< metres, lateral half-extent of the loop
    double yawAmplitudeDeg = 25, pitchAmplitudeDeg = 5, rollAmplitudeDeg = 4;
    double maxLinearSpeed = 0.5;     //!< m/s
    double maxAngularSpeedDeg = 60;  //!< deg/s
  };

  /** duration: seconds from the first to the last pose (> 0). */
  CCameraPath(const TParams& params, double duration);

  /** Pose of the camera's optical frame (+Z forward, +X right, +Y down) in the
   *  world at time t in [0, duration]; periodic in t with period duration. */
  mrpt::poses::CPose3D opticalPoseAt(double t) const;

  double duration() const { return m_duration; }
  /** Amplitude scale factors (<= 1) applied to meet the speed limits. */
  double linearScale() const { return m_linScale; }
  double angularScale() const { return m_angScale; }
  /** Maximum speeds of the final path, sampled finely (m/s, deg/s). */
  double maxLinearSpeed() const;
  double maxAngularSpeedDeg() const;

 private:
  TParams m_p;
  double m_duration;
  double m_linScale = 1, m_angScale = 1;
};
}  // namespace roislam::sim
