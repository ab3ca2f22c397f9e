/* Sequential source of RGB-D frames: the one input layer of every app.
 *
 * open() accepts either a TUM benchmark folder (rgb.txt, depth.txt, rgb/,
 * depth/) read directly, or an MRPT .rawlog of CObservation3DRangeScan (as
 * written by tum2rawlog or rawlog-grabber). Errors (missing files, malformed
 * lines, corrupt images) throw std::runtime_error naming the file and line.
 */
#pragma once

#include <roislam/io/TRGBDFrame.h>

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

  /** Opens a TUM folder or a .rawlog. cameraSpec as in resolveCamera(); for
   *  rawlogs the intrinsics stored in the observations win unless the spec is
   *  not "auto". */
  static std::unique_ptr<CFrameSource> open(
      const std::string& path, const std::string& cameraSpec = "auto");
};
}  // namespace roislam::io
