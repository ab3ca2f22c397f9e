/* When each frame of a free-running camera was taken, from stamps that jitter.
 *
 * A Kinect's colour camera takes a frame every 1/30 s on its own clock; the
 * driver stamps each frame when it arrives on the host, a few milliseconds
 * later by an amount that varies from frame to frame. fr1's colour stamps
 * lie 1.1-1.9 ms RMS (up to 3.8 ms) off a regular grid, in a repeating
 * 36 / 32 / 32 ms pattern: the images are regular, their stamps are not. At
 * fr1/rpy's 70-100 deg/s that is up to 0.4 deg between the pose a stamp
 * reads from the ground truth and the one the image shows, and the front
 * end's rolling-shutter rate (the motion over the stamps' interval) is
 * 20 % off where an interval reads 28 or 40 ms (README "Frames taken on a
 * clock").
 *
 * The clock fits t = a + b n to the recent frames' stamps, n the frame's
 * slot on the camera's clock (consecutive frames one slot apart, a dropped
 * frame leaving one empty), by least squares over the last few seconds,
 * and times each frame by its slot on that line, once five stamps in a row
 * agree with it and while they scatter around it as a jittered clock's do
 * (otherwise frames keep their stamps). It is causal: a frame is
 * timed by its own stamp and those before it, so a live camera and a
 * recording give the same times, and so do a folder and its rawlog.
 *
 * It adapts to what the stamps show rather than trusting the nominal rate:
 * the slope is fitted (a clock a fraction of a percent off 30 Hz), and the
 * clock starts again from the next stamp where the stamps stop following
 * one (a stamp more than 0.2 periods off its slot, stamps going back,
 * a gap of more than a second, a fitted rate more than 5 % off the
 * description's): such frames keep their stamps. Exactly regular stamps
 * (a render) come back as they were.
 */
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <nlohmann/json.hpp>

namespace roislam::io
{
struct TFrameClockStats
{
  std::size_t frames = 0;    //!< stamps seen
  std::size_t clocked = 0;   //!< frames timed by the clock (the others kept their stamps)
  std::size_t restarts = 0;  //!< times the stamps stopped following the clock
  /** RMS of stamp minus clock time over the clocked frames, ms: the jitter
   *  removed. */
  double rmsCorrectionMs = 0;
  double maxCorrectionMs = 0;  //!< largest |stamp - clock time|, ms
};

/** summary.json's sensor.frame_clock: frames, clocked, restarts,
 *  rms_correction_ms, max_correction_ms. */
nlohmann::json toJson(const TFrameClockStats& stats);

class CFrameClock
{
 public:
  /** frameRate: the camera's nominal rate (Hz, > 0): the first slots and the
   *  plausible range of the fitted one. Throws std::invalid_argument. */
  explicit CFrameClock(double frameRate);

  /** The time of the frame stamped `stamp` (s), the next frame in order. */
  double time(double stamp);
  /** Forget every stamp (a source rewound); statistics start again too. */
  void reset();

  const TFrameClockStats& stats() const { return m_stats; }

 private:
  struct TSlot
  {
    std::int64_t n;
    double t;  //!< stamp minus the anchor, s (keeps the fit well conditioned)
  };
  void restart(double stamp);
  /** Fitted line (offset from the anchor, period) over the window. */
  void fit(double& a, double& b) const;

  double m_period;
  std::size_t m_window;
  double m_anchor = 0;
  std::deque<TSlot> m_slots;
  double m_lastTime = 0;
  double m_sumSq = 0;
  TFrameClockStats m_stats;
};
}  // namespace roislam::io
