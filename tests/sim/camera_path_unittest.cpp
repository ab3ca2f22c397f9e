// CCameraPath: closed loop, speed limits, amount of motion.
#include <gtest/gtest.h>
#include <mrpt/core/bits_math.h>
#include <roislam/sim/CCameraPath.h>

#include <algorithm>
#include <cmath>

using roislam::sim::CCameraPath;

namespace
{
double rotationAngleDeg(const mrpt::poses::CPose3D& a, const mrpt::poses::CPose3D& b)
{
  const auto R = (b - a).getRotationMatrix();
  const double c = std::clamp((R(0, 0) + R(1, 1) + R(2, 2) - 1) / 2, -1.0, 1.0);
  return mrpt::RAD2DEG(std::acos(c));
}
}  // namespace

TEST(CameraPath, LoopIsClosed)
{
  const CCameraPath path(CCameraPath::TParams{}, 89 / 30.0);
  const auto first = path.opticalPoseAt(0), last = path.opticalPoseAt(path.duration());
  EXPECT_LT((first.translation() - last.translation()).norm(), 0.01);
  EXPECT_LT(rotationAngleDeg(first, last), 1.0);
  // Half way round it is somewhere else.
  const auto mid = path.opticalPoseAt(path.duration() / 2);
  EXPECT_GT((first.translation() - mid.translation()).norm(), 0.1);
}

TEST(CameraPath, RespectsHandheldSpeedLimitsAtFrameRate)
{
  for (const double duration : {59 / 30.0, 89 / 30.0, 299 / 30.0})
  {
    const CCameraPath path(CCameraPath::TParams{}, duration);
    const double dt = 1 / 30.0;
    double vmax = 0, wmax = 0, length = 0, yawMin = 1e9, yawMax = -1e9;
    for (double t = 0; t + dt <= duration + 1e-9; t += dt)
    {
      const auto a = path.opticalPoseAt(t), b = path.opticalPoseAt(t + dt);
      const double step = (b.translation() - a.translation()).norm();
      length += step;
      vmax = std::max(vmax, step / dt);
      wmax = std::max(wmax, rotationAngleDeg(a, b) / dt);
      // Heading of the optical axis in the world XY plane.
      const auto R = a.getRotationMatrix();
      const double yaw = mrpt::RAD2DEG(std::atan2(R(1, 2), R(0, 2)));
      yawMin = std::min(yawMin, yaw);
      yawMax = std::max(yawMax, yaw);
    }
    EXPECT_LE(vmax, 0.5) << "duration " << duration;
    EXPECT_LE(wmax, 60.0) << "duration " << duration;
    EXPECT_GT(length, 0.5) << "duration " << duration;
    EXPECT_LT(length, 2.5) << "duration " << duration;
    EXPECT_GT(yawMax - yawMin, 25.0) << "duration " << duration;  // tens of degrees of yaw
  }
}

TEST(CameraPath, LongSequencesKeepNominalAmplitude)
{
  const CCameraPath slow(CCameraPath::TParams{}, 60.0);
  EXPECT_DOUBLE_EQ(slow.linearScale(), 1.0);
  EXPECT_DOUBLE_EQ(slow.angularScale(), 1.0);
  const CCameraPath fast(CCameraPath::TParams{}, 2.0);
  EXPECT_LT(fast.linearScale(), 1.0);
}

TEST(CameraPath, RejectsBadDuration)
{
  EXPECT_THROW(CCameraPath(CCameraPath::TParams{}, 0.0), std::invalid_argument);
}
