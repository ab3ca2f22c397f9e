#include "roislam/io/CPingPongFrameSource.h"

#include <cmath>
#include <stdexcept>

namespace roislam::io
{
CPingPongFrameSource::CPingPongFrameSource(
    std::unique_ptr<CFrameSource> source, std::size_t totalFrames)
    : m_source(std::move(source)), m_total(totalFrames)
{
  if (!m_source)
    throw std::invalid_argument("CPingPongFrameSource: no source");
  if (m_source->size() < 2)
    throw std::invalid_argument(
        m_source->name() + ": a sequence played there and back needs at least 2 frames");
  rewind();
}

void CPingPongFrameSource::rewind()
{
  m_source->rewind();
  m_delivered = 0;
  m_last.reset();
}

std::size_t CPingPongFrameSource::sourceIndex(std::size_t k) const
{
  const std::size_t n = m_source->size(), period = 2 * (n - 1);
  const std::size_t phase = k % period;
  return phase < n ? phase : period - phase;
}

std::optional<TRGBDFrame> CPingPongFrameSource::next()
{
  if (m_delivered >= m_total)
    return std::nullopt;
  const std::size_t i = sourceIndex(m_delivered);
  if (!m_last || i != *m_last + 1)
    m_source->seek(i);
  auto f = m_source->next();
  if (!f)
    throw std::runtime_error(
        m_source->name() + ": frame " + std::to_string(i) + " could not be read again");
  const double sourceStamp = f->timestamp;
  const double stamp =
      m_last ? m_lastStamp + std::abs(sourceStamp - m_lastSourceStamp) : sourceStamp;
  // Played backwards, time is mirrored: a depth image taken after its colour
  // image was taken before it (the front end corrects for the offset). A
  // frame reached by a step back is played backwards.
  const bool backwards = m_last && i < *m_last;
  const double depthOffset = f->depthTimestamp - sourceStamp;
  f->depthTimestamp = stamp + (backwards ? -depthOffset : depthOffset);
  f->timestamp = stamp;
  f->index = m_delivered++;
  m_last = i;
  m_lastSourceStamp = sourceStamp;
  m_lastStamp = stamp;
  return f;
}
}  // namespace roislam::io
