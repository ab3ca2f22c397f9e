/* Sequential source of RGB-D frames: the one input layer of every app.
 *
 * open() accepts a TUM benchmark folder (rgb.txt, depth.txt, rgb/, depth/)
 * read directly, an MRPT .rawlog of CObservation3DRangeScan (as written by
 * tum2rawlog or rawlog-grabber), an OpenNI .oni recording, or a live OpenNI2
 * device ("openni2", "openni2://<uri>"). Every source holds the sensor
 * description it reads with (sensor(): depth scale, registration of
 * unregistered depth, and the camera facts the front end needs) and why it
 * was picked. Errors (missing files, malformed lines, corrupt images, no
 * device) throw std::runtime_error naming the file and line.
 */
#pragma once

#include <roislam/io/CFrameClock.h>
#include <roislam/io/TRGBDFrame.h>
#include <roislam/io/TSensorChoice.h>

#include <memory>
#include <optional>
#include <string>

namespace roislam::io
{
class CFrameSource
{
 public:
  virtual ~CFrameSource() = default;

  /** The next frame, or nullopt at the end of the sequence. */
  virtual std::optional<TRGBDFrame> next() = 0;
  /** Restart from the first frame. */
  virtual void rewind() = 0;
  /** Continue from frame `index` (0-based; next() then returns it). The
   *  default rewinds and reads up to it; sources with random access do
   *  better. Throws std::out_of_range beyond size(). */
  virtual void seek(std::size_t index);
  /** Number of frames this source will deliver in total. */
  virtual std::size_t size() const = 0;
  /** Intrinsics of the colour camera. */
  virtual const mrpt::img::TCamera& camera() const = 0;
  /** Ground-truth file in TUM format belonging to this sequence, if any
   *  (<dir>/groundtruth.txt, or <rawlog>.groundtruth.txt next to a rawlog). */
  virtual std::optional<std::string> groundTruthFile() const = 0;
  /** Accelerometer log in TUM format (TumAccelerometer.h) belonging to this
   *  sequence, if any (<dir>/accelerometer.txt, or <rawlog stem>.accelerometer.txt
   *  next to a rawlog). */
  virtual std::optional<std::string> accelerometerFile() const { return std::nullopt; }
  /** Human-readable name of the sequence (folder or file stem). */
  virtual std::string name() const = 0;
  /** Colour frames skipped because no depth image was within the association
   *  window (TUM folders only; 0 for rawlogs). */
  virtual std::size_t skippedFrames() const { return 0; }

  /** The sensor description the frames were read with, its source and the
   *  reason it was picked (printed by the apps, recorded in summary.json). */
  const TSensorChoice& sensor() const { return m_sensor; }
  /** How the frames delivered so far were timed (CFrameClock); nullopt when
   *  the description says their stamps are their times
   *  (regular_frame_clock = false). A folder times all its frames when it
   *  opens. */
  virtual std::optional<TFrameClockStats> frameClock() const;

  /** Opens a TUM folder (cameraSpec as resolveSensor()), a .rawlog or a .oni
   *  (as resolveSensorForFile(): with "auto" and no <stem>.camera.ini, a
   *  rawlog's observations and an OpenNI2 recording's device describe the
   *  camera), or an OpenNI2 device: "openni2" (the first one) or
   *  "openni2://<uri>" (COpenNI2FrameSource). */
  static std::unique_ptr<CFrameSource> open(
      const std::string& path, const std::string& cameraSpec = "auto");

 protected:
  /** When the colour image stamped `stamp`, the next frame in order, was
   *  taken: its time on the camera's clock (CFrameClock, when the
   *  description has regular_frame_clock) plus the description's
   *  colour_time_offset_ms. Every source times its frames with it, once per
   *  frame and in order (a skipped frame too); restartFrameClock() when it
   *  starts again from the first. */
  double colourTime(double stamp);
  /** A frame read from an observation with one stamp (a rawlog's, an
   *  OpenNI2 device's): colourTime() of it, and depth on the same time, so
   *  their difference stays 0. */
  void timeObservationFrame(TRGBDFrame& f)
  {
    f.depthTimestamp = f.timestamp = colourTime(f.timestamp);
  }
  void restartFrameClock() { m_clock.reset(); }

  TSensorChoice m_sensor;

 private:
  std::optional<CFrameClock> m_clock;
};
}  // namespace roislam::io
