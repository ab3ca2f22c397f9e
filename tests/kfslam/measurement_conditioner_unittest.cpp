/* CMeasurementConditioner: what the EKF is given of the landmark
 * observations. The chi-square gate drops a measurement whose point jumped
 * and passes consistent ones, and widens with the odometry's drift; the
 * re-measure interval passes a landmark once per interval; the
 * rolling-shutter rectification moves a point by the camera's motion over
 * its row's time and leaves the middle row alone. */
#include <gtest/gtest.h>
#include <mrpt/math/CMatrixFixed.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/poses/CPose3D.h>
#include <roislam/kfslam/CMeasurementConditioner.h>

#include <cmath>
#include <optional>

using namespace roislam::kfslam;
using mrpt::obs::CObservationBearingRange;
using mrpt::poses::CPose3D;

namespace
{
mrpt::img::TCamera camera()
{
  mrpt::img::TCamera c;
  c.ncols = 640;
  c.nrows = 480;
  c.setIntrinsicParamsFromValues(500, 500, 320, 240);
  return c;
}

/** A measurement of the optical-frame point p (x right, y down, z forward),
 *  sigmas 2 cm and 0.01 rad. */
CObservationBearingRange::TMeasurement measure(int32_t id, const mrpt::math::TPoint3D& p)
{
  CObservationBearingRange::TMeasurement m;
  m.landmarkID = id;
  double range, yaw, pitch;
  CPose3D().sphericalCoordinates({p.z, -p.x, -p.y}, range, yaw, pitch);
  m.range = static_cast<float>(range);
  m.yaw = static_cast<float>(yaw);
  m.pitch = static_cast<float>(pitch);
  m.covariance.setZero();
  m.covariance(0, 0) = 0.02f * 0.02f;
  m.covariance(1, 1) = m.covariance(2, 2) = 0.01f * 0.01f;
  return m;
}

CObservationBearingRange observe(
    const std::vector<std::pair<int32_t, mrpt::math::TPoint3D>>& points, double stamp)
{
  CObservationBearingRange obs;
  obs.timestamp = mrpt::Clock::fromDouble(stamp);
  for (const auto& [id, p] : points)
    obs.sensedData.push_back(measure(id, p));
  return obs;
}

mrpt::math::TPoint3D opticalOf(const CObservationBearingRange::TMeasurement& m)
{
  return {
      -m.range * std::sin(m.yaw) * std::cos(m.pitch), m.range * std::sin(m.pitch),
      m.range * std::cos(m.yaw) * std::cos(m.pitch)};
}
}  // namespace

TEST(MeasurementConditioner, GateDropsAJumpedPointAndWidensWithDrift)
{
  CMeasurementConditioner gate(false, 0, 0, 0.99);
  const CPose3D still;
  // Five consistent sightings within a few millimetres, then a 10 cm jump.
  for (int k = 0; k < 5; ++k)
  {
    const auto out = gate.condition(
        observe({{7, {0.1 + 0.002 * k, 0.0, 1.5}}}, k / 30.0), camera(), k / 30.0, still);
    EXPECT_EQ(out.sensedData.size(), 1u) << k;
  }
  auto out = gate.condition(
      observe({{7, {0.2, 0.0, 1.5}}, {8, {0.0, 0.1, 1.0}}}, 0.2), camera(), 0.2, still);
  ASSERT_EQ(out.sensedData.size(), 1u);
  EXPECT_EQ(out.sensedData[0].landmarkID, 8);  // a new landmark always passes
  EXPECT_EQ(gate.gated(), 1u);
  // The same 10 cm, after the odometry may have drifted by 10 cm per axis.
  mrpt::math::CMatrixDouble66 drift;
  drift.setZero();
  for (int k = 0; k < 3; ++k)
    drift(k, k) = 0.1 * 0.1;
  gate.addMotion(drift);
  out = gate.condition(observe({{7, {0.2, 0.0, 1.5}}}, 0.25), camera(), 0.25, still);
  EXPECT_EQ(out.sensedData.size(), 1u);
  EXPECT_EQ(gate.gated(), 1u);
  // Without a gate everything passes.
  CMeasurementConditioner none(false, 0, 0, 0);
  none.condition(observe({{7, {0.1, 0.0, 1.5}}}, 0), camera(), 0, still);
  EXPECT_EQ(
      none.condition(observe({{7, {0.5, 0.0, 1.5}}}, 0.1), camera(), 0.1, still).sensedData.size(),
      1u);
}

TEST(MeasurementConditioner, IntervalPassesALandmarkOncePerInterval)
{
  CMeasurementConditioner thin(false, 0, 0.3, 0);
  int passed = 0;
  for (int k = 0; k < 30; ++k)  // one second at 30 Hz
    passed += static_cast<int>(
        thin.condition(observe({{1, {0, 0, 1}}}, k / 30.0), camera(), k / 30.0, std::nullopt)
            .sensedData.size());
  EXPECT_EQ(passed, 4);  // frames 0, 9, 18, 27
  EXPECT_EQ(thin.skipped(), 26u);
}

TEST(MeasurementConditioner, RollingShutterMovesPointsByTheirRowsTime)
{
  const auto cam = camera();
  const double readout = 0.025, w = 1.0;  // 25 ms, 1 rad/s about the optical y axis
  // The middle row is the reference time: unchanged.
  auto m = measure(1, {0.3, 0.0, 1.5});
  const auto before = opticalOf(m);
  CMeasurementConditioner::rectify(m, cam, readout, {0, w, 0}, {0, 0, 0});
  EXPECT_NEAR(opticalOf(m).x, before.x, 1e-6);
  // The last rows were seen 12.5 ms late: rotated by 12.5 mrad about y.
  const mrpt::math::TPoint3D low(0.0, 0.72, 1.5);  // row 480 (y / z * f + cy)
  m = measure(1, low);
  CMeasurementConditioner::rectify(m, cam, readout, {0, w, 0}, {0.1, 0, 0});
  const double s = 0.5 * readout;
  const auto got = opticalOf(m);
  EXPECT_NEAR(got.x, std::cos(w * s) * low.x + std::sin(w * s) * low.z + 0.1 * s, 1e-5);
  EXPECT_NEAR(got.y, low.y, 1e-5);
  EXPECT_NEAR(got.z, -std::sin(w * s) * low.x + std::cos(w * s) * low.z, 1e-5);
  // Through condition(): two poses 1/30 s apart turning about y.
  CMeasurementConditioner rs(true, 25, 0, 0);
  rs.condition(observe({}, 0), cam, 0, CPose3D());
  const CPose3D turned = CPose3D::FromYawPitchRoll(0, w / 30, 0);  // about z of the pose
  const auto out = rs.condition(observe({{1, low}}, 1 / 30.0), cam, 1 / 30.0, turned);
  ASSERT_EQ(out.sensedData.size(), 1u);
  EXPECT_GT(std::abs(opticalOf(out.sensedData[0]).x - low.x), 1e-3);
}
