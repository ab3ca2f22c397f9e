/* Private: the depth image's time offset from the colour image, estimated
 * from the frames' stamps (depth_time_correction, RollingShutter.h
 * alignDepthTime).
 *
 * A Kinect v1 streams depth and colour from two free-running cameras at the
 * same rate, so the true offset between a colour image and the depth image
 * paired with it is a phase that changes slowly, plus whole frame periods
 * (the pairing takes the nearest depth image, before or after). The stamps
 * are not capture times, though: they carry the driver's arrival jitter
 * (TUM fr1/xyz: depth -12 to -17 ms from colour, one stream's phase; fr1/rpy:
 * 0 ms for two frames in three and 6-11 ms for the third, both streams
 * stamped on the same arrival). One frame's stamp difference is therefore
 * not its offset. The estimator takes the phase of each difference modulo
 * the frame period, their circular median over the last second as the
 * phase, and the frame's offset as that phase plus the whole periods that
 * bring it nearest to the frame's own difference.
 */
#pragma once

#include <cstddef>
#include <deque>

namespace roislam::frontend::detail
{
class CDepthTimeOffset
{
 public:
  /** The offset (s, depth minus colour) to correct the frame with these
   *  stamps by; frames in time order. */
  double update(double colourStamp, double depthStamp);
  void reset();

 private:
  double period() const;
  std::deque<double> m_intervals, m_differences;
  double m_lastColour = 0;
  bool m_haveLast = false;
};
}  // namespace roislam::frontend::detail
