// The depth images' time offset from the colour images, estimated from
// jittered stamps (libs/frontend/src/DepthTimeOffset.h).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "DepthTimeOffset.h"

using roislam::frontend::detail::CDepthTimeOffset;

namespace
{
constexpr double kPeriod = 1.0 / 30;

/** Stamps of two free-running 30 Hz cameras whose depth is captured
 *  `phase(i)` s after colour frame i, each stamp with +-jitter s of
 *  arrival noise; the depth image paired with a colour one is the nearest by
 *  stamp, as the TUM association does. Returns the largest error of the
 *  estimate against the true offset of the paired depth image, frames
 *  `from`.. only. */
template <class Phase>
double worstError(Phase phase, double jitter, int frames, int from)
{
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> J(-jitter, jitter);
  CDepthTimeOffset est;
  double worst = 0;
  for (int i = 0; i < frames; ++i)
  {
    const double colour = 100 + i * kPeriod;
    // The depth images just before and after, and their stamps.
    const double truth0 = phase(i);
    double best = 0, bestStamp = 0, bestDiff = 1e9;
    for (int k = -1; k <= 1; ++k)
    {
      const double trueOffset = truth0 + k * kPeriod;
      const double stamp = colour + trueOffset + J(rng);
      if (std::abs(stamp - colour) < bestDiff)
      {
        bestDiff = std::abs(stamp - colour);
        best = trueOffset;
        bestStamp = stamp;
      }
    }
    const double got = est.update(colour + J(rng), bestStamp);
    if (i >= from)
      worst = std::max(worst, std::abs(got - best));
  }
  return worst;
}
}  // namespace

TEST(DepthTimeOffset, FirstFrameTakesItsOwnStamps)
{
  CDepthTimeOffset est;
  EXPECT_DOUBLE_EQ(est.update(10.0, 10.012), 10.012 - 10.0);
}

TEST(DepthTimeOffset, EqualStampsGiveNoOffset)
{
  CDepthTimeOffset est;
  for (int i = 0; i < 60; ++i)
    EXPECT_EQ(est.update(5 + i * kPeriod, 5 + i * kPeriod), 0.0);
}

TEST(DepthTimeOffset, JitteredStampsGiveTheCapturePhase)
{
  // Depth half a frame before colour (fr1/xyz-like): the nearest depth image
  // is sometimes the one after. Stamps +-3 ms of jitter; the estimate is
  // within 1.5 ms of the true offset once a few frames are in, and picks
  // the right depth image (before or after) every time.
  EXPECT_LT(worstError([](int) { return -0.015; }, 0.003, 200, 10), 0.0015);
  // A phase near zero, where the phases wrap around the period.
  EXPECT_LT(worstError([](int) { return 0.0005; }, 0.003, 200, 10), 0.0015);
}

TEST(DepthTimeOffset, FollowsCamerasDriftingApart)
{
  // The two clocks drift apart by 1 ms per second (30 frames); the window of
  // a second follows it to within 1 ms of the phase plus the jitter's share.
  EXPECT_LT(worstError([](int i) { return -0.010 + 0.001 * i / 30.0; }, 0.002, 300, 30), 0.002);
}

TEST(DepthTimeOffset, ResetForgetsThePast)
{
  CDepthTimeOffset est;
  for (int i = 0; i < 40; ++i)
    est.update(i * kPeriod, i * kPeriod - 0.015);
  est.reset();
  EXPECT_DOUBLE_EQ(est.update(50.0, 50.004), 50.004 - 50.0);
}
