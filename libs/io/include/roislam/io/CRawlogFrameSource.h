/* Frame source reading an MRPT rawlog of CObservation3DRangeScan: written by
 * tum2rawlog, by our simulator, or grabbed with rawlog-grabber and OpenNI2
 * (config/rawlog-grabber-openni2.ini). Both rawlog formats are accepted:
 * observation-only and action/sensory-frame pairs. Created by
 * CFrameSource::open() for files.
 *
 * The constructor reads the whole file once (cheap: colour images are external
 * or simply skipped) to count the frames and to detect corrupt or truncated
 * files early; next() then reads one observation at a time, loads its external
 * images and releases them after conversion.
 *
 * External images: relative names are resolved against <dir>/<stem>_Images
 * (set with CImage::setImagesPathBase, because MRPT 2.5.8's
 * CRawlog::detectImagesDirectory is broken); absolute names are used as they
 * are, falling back to <dir>/<stem>_Images/<file name> when the absolute path
 * no longer exists (a rawlog moved together with its _Images folder).
 * The images path base is process-global MRPT state: next() sets it before
 * every load, so two sources interleaved in one thread are fine, but reading
 * two rawlogs concurrently from different threads is not.
 *
 * ini section [RawlogFrameSource] (TOptions):
 *   sensor_label   string  ""   only observations with this sensorLabel; empty
 *                               accepts any, but then the file must contain a
 *                               single RGB-D sensor label.
 */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <roislam/io/CFrameSource.h>

#include <deque>
#include <memory>
#include <optional>
#include <string>

namespace roislam::io
{
class CRawlogFrameSource : public CFrameSource
{
 public:
  struct TOptions : public mrpt::config::CLoadableOptions
  {
    std::string sensorLabel;

    void loadFromConfigFile(
        const mrpt::config::CConfigFileBase& cfg, const std::string& section) override;
    void saveToConfigFile(
        mrpt::config::CConfigFileBase& cfg, const std::string& section) const override;
  };

  /** Opens and scans `file`. When `cameraOverride` is set it replaces the
   *  colour intrinsics stored in the observations (and the depth intrinsics
   *  when they were equal to the colour ones). Throws std::runtime_error
   *  "<file>: ..." when missing, corrupt, truncated or without RGB-D frames. */
  CRawlogFrameSource(
      const std::string& file, const TOptions& options,
      const std::optional<mrpt::img::TCamera>& cameraOverride = std::nullopt);
  explicit CRawlogFrameSource(const std::string& file);

  std::optional<TRGBDFrame> next() override;
  void rewind() override;
  /** Reads up to the frame without loading images. */
  void seek(std::size_t index) override;
  std::size_t size() const override { return m_count; }
  const mrpt::img::TCamera& camera() const override { return m_camera; }
  std::optional<std::string> groundTruthFile() const override;
  std::optional<std::string> accelerometerFile() const override;
  std::string name() const override;

  /** Next observation as stored (external images not loaded), for tools that
   *  need the MRPT object itself; advances like next(). */
  mrpt::obs::CObservation3DRangeScan::Ptr nextObservation();
  /** Folder used for relative external image names: <dir>/<stem>_Images. */
  const std::string& imagesDirectory() const { return m_imagesDir; }

 private:
  /** Reads objects until an accepted observation is queued; false at EOF. */
  bool readMore();
  void openStream();
  bool accepts(const mrpt::obs::CObservation3DRangeScan& obs) const;
  std::string locate() const;

  std::string m_file;
  std::string m_imagesDir;
  TOptions m_options;
  std::optional<mrpt::img::TCamera> m_cameraOverride;
  mrpt::img::TCamera m_camera;
  std::size_t m_count = 0;
  std::unique_ptr<mrpt::io::CFileGZInputStream> m_in;
  std::deque<mrpt::obs::CObservation3DRangeScan::Ptr> m_pending;
  std::size_t m_objectsRead = 0;
  std::size_t m_delivered = 0;
};
}  // namespace roislam::io
