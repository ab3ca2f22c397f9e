// CFrameClock: frames of a free-running camera timed by the clock their
// jittered stamps follow, and stamps kept where they follow none.
#include <gtest/gtest.h>
#include <roislam/io/CFrameClock.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

using roislam::io::CFrameClock;

namespace
{
// fr1's pattern: stamps 36 / 32 / 32 ms apart around a 33.3 ms clock, plus
// white jitter.
double fr1LikeStampDelay(std::size_t k, std::mt19937& rng)
{
  static const double pattern[3] = {-1.3e-3, 1.3e-3, 0.0};
  std::normal_distribution<double> white(0.0, 1.0e-3);
  return 4e-3 + pattern[k % 3] + white(rng);
}
}  // namespace

TEST(FrameClock, TimesJitteredStampsByTheirClock)
{
  // A camera 0.1 % slower than its nominal 30 Hz; frame 40 dropped.
  const double period = 1.001 / 30, start = 1305031229.5;
  std::mt19937 rng(7);
  CFrameClock clock(30);
  double errorStamps = 0, errorTimes = 0;
  std::size_t counted = 0;
  for (std::size_t k = 0; k < 300; ++k)
  {
    if (k == 40)
      continue;
    const double taken = start + period * static_cast<double>(k);
    const double stamp = taken + fr1LikeStampDelay(k, rng);
    const double t = clock.time(stamp);
    if (k < 30)
      continue;  // the fit settles within a second
    // The clock times the frames up to the stamps' mean delay (4 ms), which
    // no stamp shows: colour_time_offset_ms is that camera fact.
    errorStamps += std::pow(stamp - taken - 4e-3, 2);
    errorTimes += std::pow(t - taken - 4e-3, 2);
    ++counted;
  }
  const double rmsStamps = std::sqrt(errorStamps / counted) * 1e3;
  const double rmsTimes = std::sqrt(errorTimes / counted) * 1e3;
  EXPECT_GT(rmsStamps, 1.2);
  EXPECT_LT(rmsTimes, 0.4) << "ms RMS, stamps " << rmsStamps;
  EXPECT_EQ(clock.stats().frames, 299u);
  EXPECT_EQ(clock.stats().clocked, 295u);  // from the fifth frame
  EXPECT_EQ(clock.stats().restarts, 0u);
  EXPECT_NEAR(clock.stats().rmsCorrectionMs, rmsStamps, 0.4);
}

TEST(FrameClock, RegularStampsComeBackAsTheyWere)
{
  CFrameClock clock(30);
  for (std::size_t k = 0; k < 200; ++k)
  {
    // As a TUM list gives them: to the microsecond.
    const double stamp = std::round((1305031229.5 + static_cast<double>(k) / 30) * 1e6) / 1e6;
    EXPECT_EQ(clock.time(stamp), stamp) << k;
  }
  EXPECT_LT(clock.stats().maxCorrectionMs, 1e-3);  // half a microsecond of rounding
}

TEST(FrameClock, StampsThatFollowNoClockAreKept)
{
  CFrameClock clock(30);
  std::mt19937 rng(3);
  for (std::size_t k = 0; k < 60; ++k)
    clock.time(100.0 + static_cast<double>(k) / 30 + fr1LikeStampDelay(k, rng));
  const auto before = clock.stats();
  EXPECT_EQ(before.restarts, 0u);

  // A stamp 10 ms late (more than 0.2 periods): kept, and the clock starts
  // again from it.
  const double late = 100.0 + 60.0 / 30 + 0.010 + 0.004;
  EXPECT_EQ(clock.time(late), late);
  EXPECT_EQ(clock.stats().restarts, 1u);

  // A stamp going back, two frames in one slot, a gap of two seconds: kept.
  for (const double stamp : {late - 0.005, late - 0.001, late + 2.5})
  {
    const auto restarts = clock.stats().restarts;
    EXPECT_EQ(clock.time(stamp), stamp);
    EXPECT_EQ(clock.stats().restarts, restarts + 1);
  }

  // A camera that slows to 20 Hz: after the clock restarts the frames keep
  // their stamps (a rate 50 % off is no clock at 30 Hz), never a time out of
  // order.
  CFrameClock slowing(30);
  double previous = -1;
  std::size_t kept = 0;
  for (std::size_t k = 0; k < 100; ++k)
  {
    const double stamp =
        k < 50 ? static_cast<double>(k) / 30 : 49.0 / 30 + static_cast<double>(k - 49) / 20;
    const double t = slowing.time(stamp);
    EXPECT_GT(t, previous) << k;
    previous = t;
    kept += t == stamp;
  }
  EXPECT_GT(kept, 50u);
  EXPECT_GT(slowing.stats().restarts, 0u);

  // Not a stamp.
  EXPECT_TRUE(std::isnan(clock.time(std::nan(""))));
}

TEST(FrameClock, ResetForgetsTheStamps)
{
  CFrameClock a(30), b(30);
  std::mt19937 rng(5);
  std::vector<double> stamps;
  for (std::size_t k = 0; k < 50; ++k)
    stamps.push_back(7.0 + static_cast<double>(k) / 30 + fr1LikeStampDelay(k, rng));
  for (const double s : stamps)
    a.time(s);
  a.reset();
  EXPECT_EQ(a.stats().frames, 0u);
  for (const double s : stamps)
    EXPECT_EQ(a.time(s), b.time(s));
}

TEST(FrameClock, RejectsABadRate)
{
  for (const double rate : {0.0, -30.0, std::nan(""), std::numeric_limits<double>::infinity()})
    EXPECT_THROW(CFrameClock{rate}, std::invalid_argument) << rate;
}
