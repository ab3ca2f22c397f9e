#include "roislam/io/CTum2RawlogApp.h"

#include <mrpt/system/CTicTac.h>
#include <roislam/io/CRawlogWriter.h>
#include <roislam/io/CameraPresets.h>
#include <roislam/io/ObservationConversion.h>
#include <stdlib.h>
#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <optional>
#include <stdexcept>

namespace fs = std::filesystem;

namespace roislam::io
{
namespace
{
// Removes a path on scope exit unless released (the no-partial-output rule).
class CRemoveOnExit
{
 public:
  explicit CRemoveOnExit(fs::path p) : m_path(std::move(p)) {}
  ~CRemoveOnExit()
  {
    if (m_path.empty())
      return;
    std::error_code ec;
    fs::remove_all(m_path, ec);
  }
  CRemoveOnExit(const CRemoveOnExit&) = delete;
  CRemoveOnExit& operator=(const CRemoveOnExit&) = delete;
  void release() { m_path.clear(); }
  void arm(fs::path p) { m_path = std::move(p); }

 private:
  fs::path m_path;
};

// A file copied next to the rawlog (ground truth, accelerometer log): staged
// under a temporary name, renamed by commit(), removed again on failure
// until release().
class CSideFile
{
 public:
  CSideFile(std::optional<std::string> source, fs::path target, const std::string& tempSuffix)
      : m_source(std::move(source)),
        m_target(std::move(target)),
        m_temp(m_target.string() + tempSuffix),
        m_removeTemp(m_temp),
        m_removeTarget(fs::path())
  {
    if (!m_source)
      return;
    std::error_code ec;
    fs::copy_file(*m_source, m_temp, fs::copy_options::overwrite_existing, ec);
    if (ec)
      throw std::runtime_error(m_target.string() + ": cannot write (" + ec.message() + ")");
  }
  void setPermissions(mode_t mask) const
  {
    std::error_code ec;
    if (m_source)
      fs::permissions(m_temp, static_cast<fs::perms>(0666 & ~mask), ec);
  }
  void commit()
  {
    if (!m_source)
      return;
    std::error_code ec;
    fs::rename(m_temp, m_target, ec);
    if (ec)
      throw std::runtime_error(m_target.string() + ": cannot write (" + ec.message() + ")");
    m_removeTemp.release();
    m_removeTarget.arm(m_target);
  }
  void release() { m_removeTarget.release(); }
  std::optional<std::string> written() const
  {
    return m_source ? std::optional<std::string>(m_target.string()) : std::nullopt;
  }

 private:
  std::optional<std::string> m_source;
  fs::path m_target, m_temp;
  CRemoveOnExit m_removeTemp, m_removeTarget;
};

void linkOrCopy(const fs::path& from, const fs::path& to)
{
  std::error_code ec;
  fs::create_hard_link(from, to, ec);
  if (!ec)
    return;
  fs::copy_file(from, to, fs::copy_options::overwrite_existing, ec);
  if (ec)
    throw std::runtime_error(to.string() + ": cannot write (" + ec.message() + ")");
}
}  // namespace

CTum2RawlogApp::CTum2RawlogApp(const TOptions& options)
    : mrpt::system::COutputLogger("tum2rawlog"), m_options(options)
{
  logging_enable_console_output = false;
}

CTum2RawlogApp::TResult CTum2RawlogApp::run()
{
  mrpt::system::CTicTac timer;
  const auto& o = m_options;
  if (o.input.empty())
    throw std::invalid_argument("tum2rawlog: no input folder given");
  if (o.output.empty())
    throw std::invalid_argument("tum2rawlog: no output rawlog given");

  const auto camera = resolveCamera(o.camera, o.input);
  CTumFrameSource source(o.input, camera, o.tum);
  MRPT_LOG_INFO_STREAM(
      source.directory() << ": " << source.size() << " associated frames, "
                         << source.skippedFrames() << " colour frames without depth; camera fx="
                         << camera.fx() << " fy=" << camera.fy() << " cx=" << camera.cx()
                         << " cy=" << camera.cy());

  CRawlogWriter writer(o.output, o.compressLevel);
  const fs::path rawlog(writer.file());
  const fs::path outDir = rawlog.parent_path();
  const std::string stem = rawlog.stem().string();
  const fs::path imagesDir = outDir / (stem + "_Images");

  std::string stagingName = (outDir / (stem + "_Images.partial-XXXXXX")).string();
  if (!mkdtemp(stagingName.data()))
    throw std::runtime_error(stagingName + ": cannot create folder (" + std::strerror(errno) + ")");
  const fs::path staging(stagingName);
  CRemoveOnExit removeStaging(staging);

  const float rangeUnits = static_cast<float>(1.0 / o.tum.depthScale);
  const auto& entries = source.entries();
  for (std::size_t i = 0; i < entries.size(); ++i)
  {
    const auto& e = entries[i];
    // Decoding both images validates them (corrupt file, bit depth, size).
    CTumFrameSource::readColourImage(e.rgbFile, camera);
    const cv::Mat depth = CTumFrameSource::readDepthImage(e.depthFile, camera);

    const std::string name = fs::path(e.rgbFile).filename().string();
    if (!fs::exists(staging / name))
      linkOrCopy(e.rgbFile, staging / name);

    auto obs = observationFromRawDepth(depth, rangeUnits, camera, e.rgbStamp);
    obs->intensityImage.setExternalStorage((imagesDir / name).string());
    obs->hasIntensityImage = true;
    writer.write(*obs);

    if ((i + 1) % 50 == 0 || i + 1 == entries.size())
      MRPT_LOG_INFO_STREAM("frame " << (i + 1) << " / " << entries.size());
  }

  // Ground truth and accelerometer log next to the rawlog, also via temporary names.
  TResult result;
  CSideFile groundTruth(
      source.groundTruthFile(), outDir / (stem + ".groundtruth.txt"), staging.extension().string());
  CSideFile accelerometer(
      source.accelerometerFile(), outDir / (stem + ".accelerometer.txt"),
      staging.extension().string());

  // Commit: images folder, side files, then the rawlog itself; undo on failure.
  std::error_code ec;
  const mode_t mask = ::umask(0);  // mkdtemp made the folder 0700
  ::umask(mask);
  fs::permissions(staging, static_cast<fs::perms>(0777 & ~mask), ec);
  groundTruth.setPermissions(mask);
  accelerometer.setPermissions(mask);
  if (fs::exists(imagesDir))
  {
    fs::remove_all(imagesDir, ec);
    if (ec)
      throw std::runtime_error(imagesDir.string() + ": cannot replace (" + ec.message() + ")");
  }
  fs::rename(staging, imagesDir, ec);
  if (ec)
    throw std::runtime_error(imagesDir.string() + ": cannot write (" + ec.message() + ")");
  removeStaging.release();
  CRemoveOnExit removeImages(imagesDir);
  groundTruth.commit();
  accelerometer.commit();
  writer.commit();
  removeImages.release();
  groundTruth.release();
  accelerometer.release();

  result.frames = writer.count();
  result.skipped = source.skippedFrames();
  result.rawlog = rawlog.string();
  result.imagesDir = imagesDir.string();
  result.groundTruth = groundTruth.written();
  result.accelerometer = accelerometer.written();
  result.seconds = timer.Tac();
  MRPT_LOG_INFO_STREAM(
      "wrote " << result.frames << " observations to " << result.rawlog << " in " << result.seconds
               << " s");
  return result;
}
}  // namespace roislam::io
