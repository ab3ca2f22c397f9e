#include "roislam/io/COpenNI2FrameSource.h"

#include <OpenNI.h>
#include <mrpt/img/CImage.h>
#include <roislam/io/CDepthColourCalibrator.h>
#include <roislam/io/CameraPresets.h>
#include <roislam/io/ObservationConversion.h>

#include <cmath>
#include <filesystem>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace fs = std::filesystem;

namespace roislam::io
{
namespace
{
const char* kScheme = "openni2://";

// OpenNI2's extended error text, on one line.
std::string openniError()
{
  std::string e = openni::OpenNI::getExtendedError();
  for (char& c : e)
    if (c == '\n' || c == '\t')
      c = ' ';
  const auto first = e.find_first_not_of(' '), last = e.find_last_not_of(' ');
  return first == std::string::npos ? std::string("no detail") : e.substr(first, last - first + 1);
}

// The first connected device. Not openni::ANY_DEVICE: once a process has
// played a recording, OpenNI2 lists that file as a device too.
std::string firstDeviceUri()
{
  openni::Array<openni::DeviceInfo> devices;
  openni::OpenNI::enumerateDevices(&devices);
  for (int i = 0; i < devices.getSize(); ++i)
  {
    const std::string uri = devices[i].getUri();
    if (uri.size() < 4 || uri.compare(uri.size() - 4, 4, ".oni") != 0)
      return uri;
  }
  return {};
}

std::string sizeText(int w, int h)
{
  return std::to_string(w) + "x" + std::to_string(h);
}

double depthScaleOf(openni::PixelFormat f, const std::string& input)
{
  if (f == openni::PIXEL_FORMAT_DEPTH_1_MM)
    return 1000;
  if (f == openni::PIXEL_FORMAT_DEPTH_100_UM)
    return 10000;
  throw std::runtime_error(
      input + ": unsupported OpenNI2 depth pixel format " + std::to_string(int(f)) +
      " (expected DEPTH_1_MM or DEPTH_100_UM)");
}

// A pinhole camera of the stream's resolution from its fields of view.
mrpt::img::TCamera cameraFromFov(int w, int h, double hfov, double vfov, const std::string& name)
{
  mrpt::img::TCamera c;
  c.ncols = w;
  c.nrows = h;
  c.setIntrinsicParamsFromValues(
      0.5 * w / std::tan(0.5 * hfov), 0.5 * h / std::tan(0.5 * vfov), 0.5 * (w - 1), 0.5 * (h - 1));
  c.distortion = mrpt::img::DistortionModel::none;
  c.cameraName = name;
  return c;
}

void checkResolution(
    const mrpt::img::TCamera& c, const openni::VideoMode& m, const std::string& section,
    const std::string& stream, const std::string& input)
{
  if (int(c.ncols) != m.getResolutionX() || int(c.nrows) != m.getResolutionY())
    throw std::runtime_error(
        input + ": the sensor description's [" + section + "] resolution " +
        sizeText(c.ncols, c.nrows) + " does not match the " + stream + " stream's " +
        sizeText(m.getResolutionX(), m.getResolutionY()));
}
}  // namespace

struct COpenNI2FrameSource::TStreams
{
  openni::Device device;
  openni::VideoStream depth, colour;
  ~TStreams()
  {
    depth.stop();
    colour.stop();
    // The device first: closing a recording joins the file driver's player
    // thread, which otherwise may still touch a stream destroyed under it
    // (Debian's OpenNI2 2.2 file driver: a segfault in about 1 of 15 test
    // runs on a loaded machine with streams destroyed first).
    device.close();
    depth.destroy();
    colour.destroy();
  }
};

bool COpenNI2FrameSource::isDeviceSpec(const std::string& input)
{
  return input == "openni2" || input.rfind(kScheme, 0) == 0;
}

COpenNI2FrameSource::COpenNI2FrameSource(
    const std::string& input, const std::optional<TSensorChoice>& sensor)
    : m_input(input), m_live(isDeviceSpec(input))
{
  openDevice();
  m_sensor = describe(sensor);
  auto& dev = m_streams->device;
  if (m_live && dev.isImageRegistrationModeSupported(openni::IMAGE_REGISTRATION_DEPTH_TO_COLOR))
    dev.setImageRegistrationMode(
        m_sensor.sensor.depth_registered ? openni::IMAGE_REGISTRATION_DEPTH_TO_COLOR
                                         : openni::IMAGE_REGISTRATION_OFF);
  if (!m_sensor.sensor.depth_registered && m_sensor.sensor.estimate_registration)
    estimateRegistration();
}

void COpenNI2FrameSource::estimateRegistration()
{
  const auto& sensor = m_sensor.sensor;
  if (m_live)
  {
    m_sensor.reason += "; registration not estimated (a live device: record it first)";
    return;
  }
  if (const std::string why = CDepthColourCalibrator::whyNotEstimable(sensor); !why.empty())
  {
    m_sensor.reason += "; registration not estimated (" + why + ")";
    return;
  }
  // A recording plays in order: frames evenly over its first
  // kRegistrationScan, then it plays again from the start.
  CDepthColourCalibrator calibrator(sensor);
  const std::size_t scan = std::min(m_count, kRegistrationScan);
  const std::size_t step = std::max<std::size_t>(1, scan / kRegistrationFrames);
  for (std::size_t i = 0; i < scan; ++i)
  {
    const auto obs = nextObservation();
    if (!obs)
      break;
    if (i % step != 0)
      continue;
    calibrator.addFrame(
        obs->intensityImage.asCvMat<cv::Mat>(mrpt::img::SHALLOW_COPY),
        depthMetresOnDepthGrid(*obs, m_input + ": frame " + std::to_string(i)));
  }
  rewind();
  const auto result = calibrator.estimate();
  m_sensor.reason += "; " + result.summary();
  if (result.accepted)
    m_sensor.sensor = result.sensor;
}

COpenNI2FrameSource::~COpenNI2FrameSource() = default;

void COpenNI2FrameSource::openDevice()
{
  if (openni::OpenNI::initialize() != openni::STATUS_OK)
    throw std::runtime_error(m_input + ": cannot initialise OpenNI2 (" + openniError() + ")");
  m_streams = std::make_unique<TStreams>();
  auto& s = *m_streams;
  const std::string uri = m_input == "openni2" ? firstDeviceUri()
                          : m_live             ? m_input.substr(std::string(kScheme).size())
                                               : m_input;
  if (uri.empty() || s.device.open(uri.c_str()) != openni::STATUS_OK)
    throw std::runtime_error(
        m_live ? m_input + ": no OpenNI2 device found (" +
                     (uri.empty() ? std::string("OpenNI2 lists none") : openniError()) +
                     "); connect a Kinect / Xtion or pass an .oni recording"
               : m_input + ": cannot open the OpenNI recording (" + openniError() + ")");
  if (s.depth.create(s.device, openni::SENSOR_DEPTH) != openni::STATUS_OK)
    throw std::runtime_error(m_input + ": no depth stream (" + openniError() + ")");
  if (s.colour.create(s.device, openni::SENSOR_COLOR) != openni::STATUS_OK)
    throw std::runtime_error(m_input + ": no colour stream (" + openniError() + ")");
  if (m_live)
  {
    s.device.setDepthColorSyncEnabled(true);
    // Camera images, not a mirror (OpenNI's default for some drivers).
    s.depth.setMirroringEnabled(false);
    s.colour.setMirroringEnabled(false);
  }
  else
  {
    // Manual playback: every read returns the next frame, none is dropped.
    auto* playback = s.device.getPlaybackControl();
    playback->setRepeatEnabled(false);
    playback->setSpeed(-1);
    const int n =
        std::min(playback->getNumberOfFrames(s.depth), playback->getNumberOfFrames(s.colour));
    m_count = n > 0 ? static_cast<std::size_t>(n) : 0;
  }
  if (s.depth.start() != openni::STATUS_OK || s.colour.start() != openni::STATUS_OK)
    throw std::runtime_error(m_input + ": cannot start the streams (" + openniError() + ")");
}

TSensorChoice COpenNI2FrameSource::describe(const std::optional<TSensorChoice>& given) const
{
  auto& s = *m_streams;
  const openni::VideoMode dm = s.depth.getVideoMode(), cm = s.colour.getVideoMode();
  const double scale = depthScaleOf(dm.getPixelFormat(), m_input);
  const bool deviceRegisters =
      m_live ? s.device.isImageRegistrationModeSupported(openni::IMAGE_REGISTRATION_DEPTH_TO_COLOR)
             : s.device.getImageRegistrationMode() == openni::IMAGE_REGISTRATION_DEPTH_TO_COLOR;
  TSensorChoice c;
  if (given)
  {
    c = *given;
    if (!m_live && deviceRegisters && !c.sensor.depth_registered)
      throw std::runtime_error(
          m_input +
          ": OpenNI2 registered this recording's depth to colour, but the sensor "
          "description says [SensorDescription] depth_registered = false");
  }
  else
  {
    if (!deviceRegisters)
      throw std::runtime_error(
          m_input +
          ": the depth is not registered to colour and no sensor description gives "
          "the depth-to-colour extrinsics: pass --camera FILE (config/"
          "sensor-kinect1.ini: Kinect v1 factory values) or put " +
          fs::path(sensorFileBeside(m_input)).filename().string() + " beside the recording");
    // Registered depth lies on the colour grid; a recording may report the
    // colour stream's field of view as 0, the registered depth stream's is the same.
    const bool colourFov = s.colour.getHorizontalFieldOfView() > 0;
    const auto& fovStream = colourFov ? s.colour : s.depth;
    c.sensor.name = "openni2";
    c.sensor.colour = cameraFromFov(
        cm.getResolutionX(), cm.getResolutionY(), fovStream.getHorizontalFieldOfView(),
        fovStream.getVerticalFieldOfView(), "openni2");
    c.sensor.frame_rate = cm.getFps() > 0 ? cm.getFps() : c.sensor.frame_rate;
    c.source = m_live ? "OpenNI2 device" : "OpenNI2 recording";
    c.reason =
        "--camera auto and no sensor description beside it: OpenNI2 registers depth to "
        "colour; pinhole intrinsics from the streams' fields of view, no distortion, no "
        "rolling shutter assumed (pass --camera for a calibration)";
  }
  c.sensor.depth_scale = scale;  // the stream's encoding, not a camera fact
  if (cm.getPixelFormat() != openni::PIXEL_FORMAT_RGB888)
    throw std::runtime_error(
        m_input + ": colour stream pixel format " + std::to_string(int(cm.getPixelFormat())) +
        " is not RGB888");
  checkResolution(c.sensor.colour, cm, "CAMERA_PARAMS", "colour", m_input);
  checkResolution(
      c.sensor.depth_registered ? c.sensor.colour : c.sensor.depth, dm,
      c.sensor.depth_registered ? "CAMERA_PARAMS" : "DEPTH_CAMERA_PARAMS", "depth", m_input);
  return c;
}

mrpt::obs::CObservation3DRangeScan::Ptr COpenNI2FrameSource::nextObservation()
{
  if (!m_live && m_delivered >= m_count)
    return nullptr;
  const std::string context = m_input + ": frame " + std::to_string(m_delivered);
  const int timeoutMs = m_live ? 5000 : 2000;
  const auto read = [&](openni::VideoStream& stream, const char* what)
  {
    openni::VideoStream* streams[] = {&stream};
    int ready = -1;
    openni::VideoFrameRef frame;
    if (openni::OpenNI::waitForAnyStream(streams, 1, &ready, timeoutMs) != openni::STATUS_OK ||
        stream.readFrame(&frame) != openni::STATUS_OK || !frame.isValid())
      throw std::runtime_error(
          context + ": no " + what + " frame within " + std::to_string(timeoutMs / 1000) + " s (" +
          openniError() + ")");
    return frame;
  };
  // Colour first: in a recording each colour frame precedes its depth frame.
  openni::VideoFrameRef colour = read(m_streams->colour, "colour");
  openni::VideoFrameRef depth = read(m_streams->depth, "depth");
  const cv::Mat rgb(
      colour.getHeight(), colour.getWidth(), CV_8UC3, const_cast<void*>(colour.getData()),
      static_cast<std::size_t>(colour.getStrideInBytes()));
  cv::Mat raw(
      depth.getHeight(), depth.getWidth(), CV_16UC1, const_cast<void*>(depth.getData()),
      static_cast<std::size_t>(depth.getStrideInBytes()));
  // A mirrored recording (OpenNI 1's default, e.g. the shared Kinect one) is
  // turned back into camera images, so the description's geometry holds.
  cv::Mat bgr;
  cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
  if (m_streams->colour.getMirroringEnabled())
    cv::flip(bgr, bgr, 1);
  if (m_streams->depth.getMirroringEnabled())
  {
    cv::Mat unmirrored;
    cv::flip(raw, unmirrored, 1);
    raw = unmirrored;
  }
  const double stamp = static_cast<double>(colour.getTimestamp()) * 1e-6;
  mrpt::obs::CObservation3DRangeScan::Ptr obs;
  try
  {
    obs = observationFromRawDepth(raw, m_sensor.sensor, stamp);
  }
  catch (const std::exception& e)
  {
    throw std::runtime_error(context + ": " + e.what());
  }
  obs->intensityImage = mrpt::img::CImage(bgr, mrpt::img::DEEP_COPY);
  obs->hasIntensityImage = true;
  obs->sensorLabel = "OPENNI2";
  ++m_delivered;
  return obs;
}

std::optional<TRGBDFrame> COpenNI2FrameSource::next()
{
  const std::size_t index = m_delivered;
  const auto obs = nextObservation();
  if (!obs)
    return std::nullopt;
  TRGBDFrame f = observationToFrame(*obs, m_input + ": frame " + std::to_string(index));
  f.index = index;
  timeObservationFrame(f);
  return f;
}

void COpenNI2FrameSource::rewind()
{
  if (m_live)
    return;
  m_streams.reset();
  openDevice();
  m_delivered = 0;
  restartFrameClock();
}

std::optional<std::string> COpenNI2FrameSource::groundTruthFile() const
{
  if (m_live)
    return std::nullopt;
  const fs::path p(m_input);
  const fs::path gt = p.parent_path() / (p.stem().string() + ".groundtruth.txt");
  if (fs::is_regular_file(gt))
    return gt.string();
  return std::nullopt;
}

std::string COpenNI2FrameSource::name() const
{
  return m_live ? std::string("openni2") : fs::path(m_input).stem().string();
}
}  // namespace roislam::io
