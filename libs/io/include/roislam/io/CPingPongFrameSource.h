/* Plays another frame source there and back (0, 1, ..., n-1, n-2, ..., 0, 1,
 * ...) until a given number of frames has been delivered: a long run out of a
 * short sequence without copying its data, for soak tests (memory and time
 * per frame over 10 000 frames of the shared 250-frame excerpt). Frames keep
 * their images; timestamps are remapped so that they keep increasing, each
 * step taking the original spacing of the two frames it moves between; a
 * frame's depth keeps its offset from its colour stamp, mirrored when played
 * backwards (a depth image taken after its colour image then comes before
 * it). No ground truth
 * applies to the remapped stamps (groundTruthFile() is empty). Played
 * backwards, a rolling-shutter camera reads its rows bottom to top (see the
 * README's "Rolling shutter").
 */
#pragma once

#include <roislam/io/CFrameSource.h>

#include <memory>

namespace roislam::io
{
class CPingPongFrameSource : public CFrameSource
{
 public:
  /** Throws std::invalid_argument for a null source, or one of fewer than
   *  two frames. */
  CPingPongFrameSource(std::unique_ptr<CFrameSource> source, std::size_t totalFrames);

  std::optional<TRGBDFrame> next() override;
  void rewind() override;
  std::size_t size() const override { return m_total; }
  const mrpt::img::TCamera& camera() const override { return m_source->camera(); }
  std::optional<std::string> groundTruthFile() const override { return std::nullopt; }
  std::string name() const override { return m_source->name() + "_there_and_back"; }
  std::size_t skippedFrames() const override { return m_source->skippedFrames(); }
  /** The played source's: it timed the frames, this one only remaps them. */
  std::optional<TFrameClockStats> frameClock() const override { return m_source->frameClock(); }

  /** Index in the played source of the k-th delivered frame. */
  std::size_t sourceIndex(std::size_t k) const;

 private:
  std::unique_ptr<CFrameSource> m_source;
  std::size_t m_total;
  std::size_t m_delivered = 0;
  /** Source index of the last delivered frame (to read forward without seeking). */
  std::optional<std::size_t> m_last;
  double m_lastSourceStamp = 0, m_lastStamp = 0;
};
}  // namespace roislam::io
