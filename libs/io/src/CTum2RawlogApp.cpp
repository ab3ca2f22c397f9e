#include "roislam/io/CTum2RawlogApp.h"

#include <mrpt/system/CTicTac.h>
#include <roislam/io/COpenNI2FrameSource.h>
#include <roislam/io/CRawlogWriter.h>
#include <roislam/io/CameraPresets.h>
#include <roislam/io/ObservationConversion.h>
#include <stdlib.h>
#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <vector>

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

void writeTextFile(const fs::path& file, const std::string& text)
{
  std::ofstream out(file);
  out << text;
  if (!out.flush())
    throw std::runtime_error(file.string() + ": cannot write");
}

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
/** The input named by the options: a TUM folder, an .oni recording or a live
 *  OpenNI2 device. */
std::unique_ptr<CFrameSource> openSource(const CTum2RawlogApp::TOptions& o)
{
  if (o.input.empty())
    throw std::invalid_argument("tum2rawlog: no input folder given");
  if (o.output.empty())
    throw std::invalid_argument("tum2rawlog: no output rawlog given");
  if (fs::is_directory(o.input))
    return std::make_unique<CTumFrameSource>(o.input, resolveSensor(o.camera, o.input), o.tum);
  if (COpenNI2FrameSource::isDeviceSpec(o.input) || fs::path(o.input).extension() == ".oni")
  {
    const bool live = COpenNI2FrameSource::isDeviceSpec(o.input);
    if (live && o.maxFrames == 0)
      throw std::invalid_argument(o.input + ": a live device needs --max-frames N");
    if (!live && !fs::exists(o.input))
      throw std::runtime_error(o.input + ": no such file");
    return CFrameSource::open(o.input, o.camera);
  }
  throw std::runtime_error(
      o.input + ": not a TUM folder nor an OpenNI recording (.oni) or device (openni2)");
}

/** Where the outputs go: beside the rawlog, named after its stem. */
struct TOutputPaths
{
  explicit TOutputPaths(const std::string& rawlogFile)
      : rawlog(rawlogFile),
        outDir(rawlog.parent_path()),
        stem(rawlog.stem().string()),
        imagesDir(outDir / (stem + "_Images"))
  {
  }
  /** DIR/NAME<suffix> */
  fs::path beside(const std::string& suffix) const { return outDir / (stem + suffix); }

  fs::path rawlog, outDir;
  std::string stem;
  fs::path imagesDir;
};

/** A new, empty folder to stage the images in (0700, as mkdtemp makes it). */
fs::path makeStagingFolder(const TOutputPaths& out)
{
  std::string stagingName = out.beside("_Images.partial-XXXXXX").string();
  if (!mkdtemp(stagingName.data()))
    throw std::runtime_error(stagingName + ": cannot create folder (" + std::strerror(errno) + ")");
  return fs::path(stagingName);
}

/** The sensor description, written into the staging folder; returns its path. */
fs::path writeSensorDescription(const CFrameSource& source, const fs::path& staging)
{
  // The sensor description travels with the rawlog (<stem>.camera.ini): the
  // readout, noise and rate that the observations cannot carry.
  const fs::path sensorText = staging / "sensor-description.ini";
  writeTextFile(sensorText, source.sensor().sensor.toIniText());
  return sensorText;
}

/** Moves the staging folder to imagesDir, replacing an existing one. */
void publishImages(const fs::path& staging, const fs::path& imagesDir)
{
  std::error_code ec;
  if (fs::exists(imagesDir))
  {
    fs::remove_all(imagesDir, ec);
    if (ec)
      throw std::runtime_error(imagesDir.string() + ": cannot replace (" + ec.message() + ")");
  }
  fs::rename(staging, imagesDir, ec);
  if (ec)
    throw std::runtime_error(imagesDir.string() + ": cannot write (" + ec.message() + ")");
}

// Commit: images folder, side files, then the rawlog itself; undo on failure.
void commitOutputs(
    const fs::path& staging, CRemoveOnExit& removeStaging, const fs::path& imagesDir,
    const std::vector<CSideFile*>& sideFiles, CRawlogWriter& writer)
{
  const mode_t mask = ::umask(0);  // mkdtemp made the folder 0700
  ::umask(mask);
  std::error_code ec;
  fs::permissions(staging, static_cast<fs::perms>(0777 & ~mask), ec);
  for (const CSideFile* f : sideFiles)
    f->setPermissions(mask);
  publishImages(staging, imagesDir);
  removeStaging.release();
  CRemoveOnExit removeImages(imagesDir);
  for (CSideFile* f : sideFiles)
    f->commit();
  writer.commit();
  removeImages.release();
  for (CSideFile* f : sideFiles)
    f->release();
}
}  // namespace

void CTum2RawlogApp::writeTumFrames(
    const CTumFrameSource& source, CRawlogWriter& writer, const fs::path& staging,
    const fs::path& imagesDir)
{
  const TSensorDescription& sensor = source.sensor().sensor;
  const mrpt::img::TCamera& depthCamera = sensor.depth_registered ? sensor.colour : sensor.depth;
  const auto& entries = source.entries();
  const std::size_t n =
      m_options.maxFrames ? std::min(m_options.maxFrames, entries.size()) : entries.size();
  for (std::size_t i = 0; i < n; ++i)
  {
    const auto& e = entries[i];
    // Decoding both images validates them (corrupt file, bit depth, size).
    CTumFrameSource::readColourImage(e.rgbFile, sensor.colour);
    const cv::Mat depth = CTumFrameSource::readDepthImage(e.depthFile, depthCamera);

    const std::string name = fs::path(e.rgbFile).filename().string();
    if (!fs::exists(staging / name))
      linkOrCopy(e.rgbFile, staging / name);

    auto obs = observationFromRawDepth(depth, sensor, e.rgbStamp);
    obs->intensityImage.setExternalStorage((imagesDir / name).string());
    obs->hasIntensityImage = true;
    writer.write(*obs);

    if ((i + 1) % 50 == 0 || i + 1 == n)
      MRPT_LOG_INFO_STREAM("frame " << (i + 1) << " / " << n);
  }
}

void CTum2RawlogApp::writeOpenNI2Frames(
    COpenNI2FrameSource& source, CRawlogWriter& writer, const fs::path& staging,
    const fs::path& imagesDir)
{
  const std::size_t max = m_options.maxFrames;
  for (std::size_t i = 0; max == 0 || i < max; ++i)
  {
    const auto obs = source.nextObservation();
    if (!obs)
      break;
    // The colour as a lossless PNG beside the rawlog, like a TUM folder's.
    char name[32];
    std::snprintf(name, sizeof(name), "colour_%06zu.png", i);
    if (!obs->intensityImage.saveToFile((staging / name).string()))
      throw std::runtime_error((staging / name).string() + ": cannot write");
    obs->intensityImage.setExternalStorage((imagesDir / name).string());
    writer.write(*obs);
    if ((i + 1) % 50 == 0 || i + 1 == source.size())
      MRPT_LOG_INFO_STREAM("frame " << (i + 1) << " / " << source.size());
  }
}

CTum2RawlogApp::CTum2RawlogApp(const TOptions& options)
    : mrpt::system::COutputLogger("tum2rawlog"), m_options(options)
{
  logging_enable_console_output = false;
}

CTum2RawlogApp::TResult CTum2RawlogApp::run()
{
  mrpt::system::CTicTac timer;
  const std::unique_ptr<CFrameSource> source = openSource(m_options);
  MRPT_LOG_INFO_STREAM(
      source->name() << ": " << source->size() << " frames, " << source->skippedFrames()
                     << " colour frames without depth; " << source->sensor().summary());

  CRawlogWriter writer(m_options.output, m_options.compressLevel);
  const TOutputPaths out(writer.file());
  const fs::path staging = makeStagingFolder(out);
  CRemoveOnExit removeStaging(staging);

  if (auto* tum = dynamic_cast<CTumFrameSource*>(source.get()))
    writeTumFrames(*tum, writer, staging, out.imagesDir);
  else
    writeOpenNI2Frames(static_cast<COpenNI2FrameSource&>(*source), writer, staging, out.imagesDir);

  const fs::path sensorText = writeSensorDescription(*source, staging);
  // Ground truth and accelerometer log next to the rawlog, also via temporary names.
  const std::string tempSuffix = staging.extension().string();
  CSideFile groundTruth(source->groundTruthFile(), out.beside(".groundtruth.txt"), tempSuffix);
  CSideFile accelerometer(
      source->accelerometerFile(), out.beside(".accelerometer.txt"), tempSuffix);
  CSideFile sensorFile(sensorText.string(), out.beside(".camera.ini"), tempSuffix);
  fs::remove(sensorText);
  commitOutputs(
      staging, removeStaging, out.imagesDir, {&groundTruth, &accelerometer, &sensorFile}, writer);

  TResult result;
  result.frames = writer.count();
  result.skipped = source->skippedFrames();
  result.sensorFile = sensorFile.written();
  result.rawlog = out.rawlog.string();
  result.imagesDir = out.imagesDir.string();
  result.groundTruth = groundTruth.written();
  result.accelerometer = accelerometer.written();
  result.seconds = timer.Tac();
  MRPT_LOG_INFO_STREAM(
      "wrote " << result.frames << " observations to " << result.rawlog << " in " << result.seconds
               << " s");
  return result;
}
}  // namespace roislam::io
