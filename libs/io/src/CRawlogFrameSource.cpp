#include "roislam/io/CRawlogFrameSource.h"

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/img/CImage.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/serialization/CArchive.h>
#include <roislam/io/CameraAxes.h>
#include <roislam/io/CameraPresets.h>
#include <roislam/io/ObservationConversion.h>

#include <filesystem>
#include <set>
#include <stdexcept>

#include "MrptErrorText.h"

namespace fs = std::filesystem;
using mrpt::obs::CObservation3DRangeScan;

namespace roislam::io
{
namespace detail
{
void linkThrowingAlignedMalloc();  // MrptAlignedMalloc.cpp
}

namespace
{
bool isRgbd(const CObservation3DRangeScan& o)
{
  return o.hasRangeImage && o.hasIntensityImage;
}

// What an observation says about its sensor (the rest: TSensorDescription's
// defaults, i.e. a global shutter).
TSensorDescription sensorOfObservation(const CObservation3DRangeScan& o, const std::string& name)
{
  TSensorDescription d;
  d.name = name;
  d.colour = o.cameraParamsIntensity;
  d.depth = o.cameraParams;
  d.depth_scale = o.rangeUnits > 0 ? 1.0 / double(o.rangeUnits) : d.depth_scale;
  d.depth_registered = o.doDepthAndIntensityCamerasCoincide() &&
                       o.cameraParams.ncols == o.cameraParamsIntensity.ncols &&
                       o.cameraParams.nrows == o.cameraParamsIntensity.nrows &&
                       o.cameraParams.intrinsicParams == o.cameraParamsIntensity.intrinsicParams;
  if (!d.depth_registered)
    d.depth_pose_in_colour = depthPoseInColour(o);
  return d;
}
}  // namespace

void CRawlogFrameSource::TOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section)
{
  sensorLabel = cfg.read_string(section, "sensor_label", sensorLabel);
}

void CRawlogFrameSource::TOptions::saveToConfigFile(
    mrpt::config::CConfigFileBase& cfg, const std::string& section) const
{
  cfg.write(section, "sensor_label", sensorLabel);
}

CRawlogFrameSource::CRawlogFrameSource(const std::string& file)
    : CRawlogFrameSource(file, TOptions())
{
}

CRawlogFrameSource::CRawlogFrameSource(
    const std::string& file, const TOptions& options,
    const std::optional<mrpt::img::TCamera>& cameraOverride)
    : m_options(options), m_cameraOverride(cameraOverride)
{
  detail::linkThrowingAlignedMalloc();
  if (!fs::is_regular_file(file))
    throw std::runtime_error(file + ": rawlog file not found");
  const fs::path abs = fs::absolute(file).lexically_normal();
  m_file = abs.string();
  m_imagesDir = (abs.parent_path() / (abs.stem().string() + "_Images")).string();

  // Counting pass: validates the whole file and the sensor labels.
  std::set<std::string> labels;
  std::optional<mrpt::img::TCamera> firstCamera;
  std::optional<TSensorDescription> firstSensor;
  openStream();
  while (readMore())
  {
    while (!m_pending.empty())
    {
      const auto& o = *m_pending.front();
      labels.insert(o.sensorLabel);
      if (!firstCamera)
      {
        firstCamera = o.cameraParamsIntensity;
        firstSensor = sensorOfObservation(o, fs::path(m_file).stem().string());
      }
      ++m_count;
      m_pending.pop_front();
    }
  }
  if (m_count == 0)
    throw std::runtime_error(
        m_file + ": no CObservation3DRangeScan with range and intensity images" +
        (m_options.sensorLabel.empty() ? std::string()
                                       : " and sensorLabel '" + m_options.sensorLabel + "'"));
  if (labels.size() > 1)
  {
    std::string list;
    for (const auto& l : labels)
      list += (list.empty() ? "" : ", ") + l;
    throw std::runtime_error(
        m_file + ": RGB-D observations from several sensors (" + list +
        "); choose one with [RawlogFrameSource] sensor_label");
  }
  // The frames' camera (observationToFrame flips a camera declared with a
  // negative focal length; CameraAxes.h).
  const mrpt::img::TCamera declared = m_cameraOverride ? *m_cameraOverride : *firstCamera;
  m_camera = withPositiveFocalLengths(declared);
  m_sensor = {
      *firstSensor, "rawlog observations",
      "--camera auto and no " + fs::path(sensorFileBeside(m_file)).filename().string() +
          " beside the rawlog: the observations' intrinsics, depth units and registration; "
          "no rolling shutter assumed (pass --camera for the real camera)"};
  m_sensor.sensor.colour = declared;
  rewind();
}

void CRawlogFrameSource::openStream()
{
  m_in = std::make_unique<mrpt::io::CFileGZInputStream>();
  if (!m_in->open(m_file))
    throw std::runtime_error(m_file + ": cannot open rawlog");
  m_pending.clear();
  m_objectsRead = 0;
}

void CRawlogFrameSource::rewind()
{
  openStream();
  m_delivered = 0;
  restartFrameClock();
}

void CRawlogFrameSource::seek(std::size_t index)
{
  if (index >= m_count)
    throw std::out_of_range(m_file + ": no frame " + std::to_string(index));
  rewind();
  // The skipped frames' stamps still time the ones after them (CFrameClock).
  for (; m_delivered < index; ++m_delivered)
    if (const auto obs = nextObservation())
      colourTime(mrpt::Clock::toDouble(obs->timestamp));
}

bool CRawlogFrameSource::accepts(const CObservation3DRangeScan& obs) const
{
  return isRgbd(obs) && (m_options.sensorLabel.empty() || obs.sensorLabel == m_options.sensorLabel);
}

std::string CRawlogFrameSource::locate() const
{
  return m_file + ": object " + std::to_string(m_objectsRead + 1);
}

bool CRawlogFrameSource::readMore()
{
  // Own loop instead of CRawlog::getActionObservationPairOrObservation: that
  // one prints and swallows deserialisation errors, so a truncated file would
  // look like a shorter, valid one.
  auto arch = mrpt::serialization::archiveFrom(*m_in);
  while (m_pending.empty())
  {
    const uint64_t before = m_in->getPosition();
    mrpt::serialization::CSerializable::Ptr obj;
    try
    {
      arch >> obj;
    }
    catch (const std::exception& e)
    {
      // EOF exactly at an object boundary is the normal end of the file.
      const bool atBoundary = m_in->getPosition() == before;
      if (atBoundary && dynamic_cast<const mrpt::serialization::CExceptionEOF*>(&e))
        return false;
      if (atBoundary && m_in->checkEOF())
        return false;
      throw std::runtime_error(
          locate() + ": corrupt or truncated rawlog: " + detail::oneLineError(e.what()));
    }
    ++m_objectsRead;
    if (!obj)
      continue;
    if (auto o = std::dynamic_pointer_cast<CObservation3DRangeScan>(obj))
    {
      if (accepts(*o))
        m_pending.push_back(o);
    }
    else if (auto sf = std::dynamic_pointer_cast<mrpt::obs::CSensoryFrame>(obj))
    {
      for (const auto& so : *sf)
        if (auto o3 = std::dynamic_pointer_cast<CObservation3DRangeScan>(so); o3 && accepts(*o3))
          m_pending.push_back(o3);
    }
    // Actions (odometry) and other observation types are not frames.
  }
  return true;
}

CObservation3DRangeScan::Ptr CRawlogFrameSource::nextObservation()
{
  if (m_pending.empty() && !readMore())
    return nullptr;
  auto o = m_pending.front();
  m_pending.pop_front();
  return o;
}

std::optional<TRGBDFrame> CRawlogFrameSource::next()
{
  auto obs = nextObservation();
  if (!obs)
    return std::nullopt;
  const std::string context = m_file + ": frame " + std::to_string(m_delivered);

  mrpt::img::CImage::setImagesPathBase(m_imagesDir);
  if (obs->intensityImage.isExternallyStored())
  {
    const std::string stored = obs->intensityImage.getExternalStorageFile();
    if (!stored.empty() && stored.front() == '/' && !fs::exists(stored))
    {
      const fs::path local = fs::path(m_imagesDir) / fs::path(stored).filename();
      if (fs::exists(local))
        obs->intensityImage.setExternalStorage(local.string());
    }
  }
  try
  {
    obs->load();
  }
  catch (const std::exception& e)
  {
    std::string what = obs->rangeImage_isExternallyStored()
                           ? " '" + obs->rangeImage_getExternalStorageFileAbsolutePath("") + "'"
                           : std::string();
    throw std::runtime_error(context + ": cannot load external data" + what);
  }
  if (m_cameraOverride)
  {
    const bool same =
        obs->cameraParams.ncols == obs->cameraParamsIntensity.ncols &&
        obs->cameraParams.nrows == obs->cameraParamsIntensity.nrows &&
        obs->cameraParams.intrinsicParams == obs->cameraParamsIntensity.intrinsicParams;
    obs->cameraParamsIntensity = *m_cameraOverride;
    if (same)
      obs->cameraParams = *m_cameraOverride;
  }
  TRGBDFrame f = observationToFrame(*obs, context);
  f.index = m_delivered++;
  // tum2rawlog writes the colour stamp as it was.
  timeObservationFrame(f);
  if (obs->intensityImage.isExternallyStored())
    f.rgbSource = obs->intensityImage.getExternalStorageFileAbsolutePath();
  obs->unload();
  return f;
}

std::optional<std::string> CRawlogFrameSource::groundTruthFile() const
{
  const fs::path p(m_file);
  // NAME.groundtruth.txt as tum2rawlog writes it; NAME.rawlog.groundtruth.txt also accepted.
  for (const auto& gt :
       {p.parent_path() / (p.stem().string() + ".groundtruth.txt"),
        fs::path(m_file + ".groundtruth.txt")})
    if (fs::is_regular_file(gt))
      return gt.string();
  return std::nullopt;
}

std::optional<std::string> CRawlogFrameSource::accelerometerFile() const
{
  const fs::path p(m_file);
  const fs::path file = p.parent_path() / (p.stem().string() + ".accelerometer.txt");
  if (fs::is_regular_file(file))
    return file.string();
  return std::nullopt;
}

std::string CRawlogFrameSource::name() const
{
  return fs::path(m_file).stem().string();
}
}  // namespace roislam::io
