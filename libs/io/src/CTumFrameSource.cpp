#include "roislam/io/CTumFrameSource.h"

#include <mrpt/config/CConfigFileBase.h>
#include <roislam/common/IniRead.h>
#include <roislam/io/CDepthColourCalibrator.h>
#include <roislam/io/CameraAxes.h>
#include <roislam/io/ObservationConversion.h>
#include <roislam/io/SevenScenes.h>
#include <roislam/io/StampAssociation.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <vector>

namespace fs = std::filesystem;

namespace roislam::io
{
namespace
{
struct TListItem
{
  double stamp = 0;
  std::string file;
  /** "<list>:<line>" where it is listed, for errors. */
  std::string where;
};

// rgb.txt / depth.txt: "timestamp filename" per line, '#' comments; like the
// benchmark scripts, commas and tabs also separate fields.
std::vector<TListItem> readList(const fs::path& file)
{
  std::ifstream in(file);
  if (!in)
    throw std::runtime_error(file.string() + ": cannot open");
  std::vector<TListItem> items;
  std::string line;
  std::size_t lineNo = 0;
  while (std::getline(in, line))
  {
    ++lineNo;
    if (!line.empty() && line.back() == '\r')
      line.pop_back();
    const auto first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#')
      continue;
    std::replace(line.begin(), line.end(), ',', ' ');
    std::replace(line.begin(), line.end(), '\t', ' ');
    std::istringstream ss(line);
    std::string stampText, name, extra;
    ss >> stampText >> name;
    const auto where = file.string() + ":" + std::to_string(lineNo) + ": ";
    if (name.empty())
      throw std::runtime_error(where + "expected 'timestamp filename', got '" + line + "'");
    const auto stamp = common::parseDouble(stampText);
    if (!stamp)
      throw std::runtime_error(where + "invalid timestamp '" + stampText + "'");
    if (ss >> extra)
      throw std::runtime_error(where + "expected 'timestamp filename', got '" + line + "'");
    items.push_back({*stamp, name, file.string() + ":" + std::to_string(lineNo)});
  }
  if (in.bad())
    throw std::runtime_error(file.string() + ": read error");
  return items;
}

void checkSize(const cv::Mat& img, const std::string& file, const mrpt::img::TCamera& camera)
{
  if (img.cols != static_cast<int>(camera.ncols) || img.rows != static_cast<int>(camera.nrows))
    throw std::runtime_error(
        file + ": image is " + std::to_string(img.cols) + "x" + std::to_string(img.rows) +
        " but the camera intrinsics are for " + std::to_string(camera.ncols) + "x" +
        std::to_string(camera.nrows));
}

/** A PNG ends with its IEND chunk; a truncated one does not. Checked here
 *  because libpng would print its own error on stderr before OpenCV fails. */
bool isTruncatedPng(const std::vector<unsigned char>& bytes)
{
  static const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  static const unsigned char iend[12] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xae, 0x42, 0x60, 0x82};
  if (bytes.size() < 8 || !std::equal(signature, signature + 8, bytes.begin()))
    return false;  // not a PNG: left to the decoder
  return bytes.size() < 8 + 12 || !std::equal(iend, iend + 12, bytes.end() - 12);
}

/** A 16-bit depth PNG's "no reading" besides 0: 7-Scenes writes 65535
 *  (65.5 m in millimetres, no RGB-D camera's range; 13.1 m at TUM's 5000). */
constexpr uint16_t kNoDepthReading = 0xFFFF;

cv::Mat readImage(const std::string& file, int flags)
{
  if (!fs::is_regular_file(file))
    throw std::runtime_error(file + ": image file not found");
  std::ifstream in(file, std::ios::binary | std::ios::ate);
  std::vector<unsigned char> bytes(in ? static_cast<std::size_t>(in.tellg()) : 0);
  in.seekg(0);
  if (!in || !in.read(reinterpret_cast<char*>(bytes.data()), bytes.size()))
    throw std::runtime_error(file + ": read error");
  if (isTruncatedPng(bytes))
    throw std::runtime_error(file + ": cannot decode image (truncated PNG: no IEND chunk)");
  cv::Mat img;
  try
  {
    img = cv::imdecode(bytes, flags);
  }
  catch (const cv::Exception&)
  {
    img.release();
  }
  if (img.empty())
    throw std::runtime_error(file + ": cannot decode image (corrupt or not an image)");
  return img;
}
}  // namespace

void CTumFrameSource::TOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section)
{
  maxTimeDifference = cfg.read_double(section, "max_time_difference", maxTimeDifference);
  depthScale = cfg.read_double(section, "depth_scale", depthScale);
  if (!(maxTimeDifference > 0))
    throw std::invalid_argument("[" + section + "] max_time_difference must be > 0");
  if (!(depthScale > 0))
    throw std::invalid_argument("[" + section + "] depth_scale must be > 0");
}

void CTumFrameSource::TOptions::saveToConfigFile(
    mrpt::config::CConfigFileBase& cfg, const std::string& section) const
{
  cfg.write(section, "max_time_difference", maxTimeDifference);
  cfg.write(section, "depth_scale", depthScale);
}

namespace
{
TSensorChoice registeredSensor(const mrpt::img::TCamera& camera, double depthScale)
{
  TSensorChoice c;
  c.sensor.name = camera.cameraName.empty() ? "camera" : camera.cameraName;
  c.sensor.colour = camera;
  c.sensor.depth_scale = depthScale;
  c.source = "intrinsics given in code";
  c.reason = "CTumFrameSource(dir, camera): registered depth, no rolling shutter";
  return c;
}

CTumFrameSource::TOptions withScale(CTumFrameSource::TOptions o, double depthScale)
{
  o.depthScale = depthScale;
  return o;
}
}  // namespace

CTumFrameSource::CTumFrameSource(
    const std::string& dir, const mrpt::img::TCamera& camera, const TOptions& options)
    : CTumFrameSource(dir, registeredSensor(camera, options.depthScale), options)
{
}

CTumFrameSource::CTumFrameSource(
    const std::string& dir, const TSensorChoice& choice, const TOptions& options)
    : m_camera(withPositiveFocalLengths(choice.sensor.colour)),
      m_depthCamera(withPositiveFocalLengths(
          choice.sensor.depth_registered ? choice.sensor.colour : choice.sensor.depth)),
      m_options(withScale(options, choice.sensor.depth_scale))
{
  m_sensor = choice;
  if (!fs::is_directory(dir))
    throw std::runtime_error(dir + ": dataset folder not found");
  if (!(options.maxTimeDifference > 0) || !(m_options.depthScale > 0))
    throw std::invalid_argument("CTumFrameSource: maxTimeDifference and depthScale must be > 0");
  for (const mrpt::img::TCamera* c : {&m_camera, &m_depthCamera})
    if (c->ncols == 0 || c->nrows == 0 || !(c->fx() > 0) || !(c->fy() > 0))
      throw std::invalid_argument(dir + ": camera intrinsics are not set");
  const fs::path root = fs::absolute(dir).lexically_normal();
  m_dir = root.string();
  if (!m_dir.empty() && m_dir.back() == '/' && m_dir.size() > 1)
    m_dir.pop_back();

  if (isSevenScenesFolder(m_dir))
  {
    readSevenScenesFolder();
    return;
  }
  const auto rgb = readList(root / "rgb.txt");
  const auto depth = readList(root / "depth.txt");

  if (rgb.empty())
    throw std::runtime_error((root / "rgb.txt").string() + ": no frames listed");
  if (depth.empty())
    throw std::runtime_error((root / "depth.txt").string() + ": no frames listed");

  std::vector<double> rgbStamps, depthStamps;
  for (const auto& r : rgb)
    rgbStamps.push_back(r.stamp);
  for (const auto& d : depth)
    depthStamps.push_back(d.stamp);
  const auto pairs = associateStamps(rgbStamps, depthStamps, options.maxTimeDifference);

  for (const auto& [i, j] : pairs)
  {
    TEntry e;
    e.rgbStamp = rgb[i].stamp;
    e.depthStamp = depth[j].stamp;
    e.rgbFile = (root / rgb[i].file).lexically_normal().string();
    e.depthFile = (root / depth[j].file).lexically_normal().string();
    for (const auto& [f, where] :
         {std::pair(e.rgbFile, rgb[i].where), {e.depthFile, depth[j].where}})
      if (!fs::is_regular_file(f))
        throw std::runtime_error(where + ": image file not found: " + f);
    m_entries.push_back(std::move(e));
  }
  std::stable_sort(
      m_entries.begin(), m_entries.end(),
      [](const TEntry& a, const TEntry& b) { return a.rgbStamp < b.rgbStamp; });
  m_skipped = rgb.size() - pairs.size();
  if (m_entries.empty())
    throw std::runtime_error(
        m_dir + ": no colour frame has a depth image within " +
        std::to_string(options.maxTimeDifference) + " s");
  estimateRegistration();
  timeFrames();
}

void CTumFrameSource::timeFrames()
{
  // In order, once each, before any seek: a frame's time depends on the
  // stamps before it (CFrameClock), as it does when a rawlog of this folder
  // is read.
  restartFrameClock();
  for (TEntry& e : m_entries)
    e.time = colourTime(e.rgbStamp);
}

void CTumFrameSource::estimateRegistration()
{
  const TSensorDescription& sensor = m_sensor.sensor;
  if (sensor.depth_registered || !sensor.estimate_registration)
    return;
  if (const std::string why = CDepthColourCalibrator::whyNotEstimable(sensor); !why.empty())
  {
    m_sensor.reason += "; registration not estimated (" + why + ")";
    return;
  }
  // Frames spread evenly over the whole sequence: the edges of many views,
  // and the colour camera's rolling shutter (its edges moved against the
  // depth ones by the motion) averages out as well as it can. Picking the
  // stillest of three candidates each was worse on renders: the estimated
  // cy moved 5-9 px (fewer views, alike).
  CDepthColourCalibrator calibrator(sensor);
  const std::size_t n = std::min(kRegistrationFrames, m_entries.size());
  for (std::size_t k = 0; k < n; ++k)
  {
    const auto [rgb, depth] = readRawFrame(m_entries[k * m_entries.size() / n]);
    calibrator.addFrame(rgb, depth);
  }
  const auto result = calibrator.estimate();
  m_sensor.reason += "; " + result.summary();
  if (!result.accepted)
    return;
  m_sensor.sensor = result.sensor;
  m_camera = withPositiveFocalLengths(m_sensor.sensor.colour);
}

CTumFrameSource::CTumFrameSource(const std::string& dir, const mrpt::img::TCamera& camera)
    : CTumFrameSource(dir, camera, TOptions())
{
}

CTumFrameSource::~CTumFrameSource()
{
  if (!m_groundTruthTemp.empty())
  {
    std::error_code ec;
    fs::remove_all(fs::path(m_groundTruthTemp).parent_path(), ec);
  }
}

void CTumFrameSource::readSevenScenesFolder()
{
  const TSensorDescription& sensor = m_sensor.sensor;
  const auto frames = listSevenScenesFrames(m_dir);
  for (const auto& f : frames)
  {
    // No timestamps in the layout: frame numbers at the camera's frame rate.
    const double stamp = static_cast<double>(f.number) / sensor.frame_rate;
    m_entries.push_back({stamp, stamp, f.colourFile, f.depthFile});
  }
  // Before the ground truth: it is turned into the colour camera's poses
  // through the (estimated) depth pose.
  estimateRegistration();
  timeFrames();
  const auto gt = loadSevenScenesGroundTruth(
      frames, sensor.frame_rate,
      sensor.depth_registered ? mrpt::poses::CPose3D() : sensor.depth_pose_in_colour);
  if (gt.empty())
    return;
  // The apps take the ground truth as a TUM file (evaluation, tum2rawlog's
  // side file, the live view): it is written once, to a folder of this
  // source's own under the system's temporary folder, removed with it.
  std::error_code ec;
  const fs::path tmpRoot = fs::temp_directory_path(ec);
  if (ec)
    throw std::runtime_error(
        "no temporary folder for " + m_dir + "'s ground truth: " + ec.message());
  static std::atomic<unsigned> counter{0};
  const fs::path folder =
      tmpRoot / ("roislam-7scenes-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  fs::create_directories(folder, ec);
  if (ec)
    throw std::runtime_error(folder.string() + ": cannot create: " + ec.message());
  const std::string file = (folder / "groundtruth.txt").string();
  try
  {
    saveTumTrajectory(
        file, gt,
        "ground truth of " + m_dir +
            " (7-Scenes frame-NNNNNN.pose.txt, the colour camera's pose; time = frame number / " +
            "frame_rate)");
  }
  catch (...)
  {
    fs::remove_all(folder, ec);
    throw;
  }
  m_groundTruthTemp = file;
}

cv::Mat CTumFrameSource::readColourImage(const std::string& file, const mrpt::img::TCamera& camera)
{
  cv::Mat img = readImage(file, cv::IMREAD_COLOR);
  checkSize(img, file, camera);
  return img;
}

cv::Mat CTumFrameSource::readDepthImage(const std::string& file, const mrpt::img::TCamera& camera)
{
  cv::Mat img = readImage(file, cv::IMREAD_UNCHANGED);
  if (img.type() != CV_16UC1)
    throw std::runtime_error(
        file + ": depth image must be single-channel 16-bit (got " +
        std::to_string(img.channels()) + " channel(s) of " + std::to_string(8 * img.elemSize1()) +
        " bits)");
  checkSize(img, file, camera);
  return img;
}

void CTumFrameSource::seek(std::size_t index)
{
  if (index >= m_entries.size())
    throw std::out_of_range(m_dir + ": no frame " + std::to_string(index));
  m_next = index;
}

std::pair<cv::Mat, cv::Mat> CTumFrameSource::readRawFrame(const TEntry& e) const
{
  const TSensorDescription& sensor = m_sensor.sensor;
  cv::Mat rgb = readColourImage(e.rgbFile, m_camera);
  cv::Mat raw = readDepthImage(e.depthFile, m_depthCamera);
  // A camera declared with a negative focal length (ICL-NUIM's fy < 0): the
  // frames carry the flipped images and m_camera (CameraAxes.h).
  flipToPositiveFocalLengths(rgb, sensor.colour);
  flipToPositiveFocalLengths(raw, sensor.depth_registered ? sensor.colour : sensor.depth);
  // Exact float(raw / scale) per pixel (cv::convertTo scales in float and can
  // be one ulp off), so rawlog and folder readers agree bit for bit.
  cv::Mat depth(raw.size(), CV_32FC1);
  const double scale = m_options.depthScale;
  for (int r = 0; r < raw.rows; ++r)
  {
    const auto* src = raw.ptr<uint16_t>(r);
    auto* dst = depth.ptr<float>(r);
    for (int c = 0; c < raw.cols; ++c)
      dst[c] = src[c] == kNoDepthReading ? 0.0f : static_cast<float>(src[c] / scale);
  }
  return {rgb, depth};
}

std::optional<TRGBDFrame> CTumFrameSource::next()
{
  if (m_next >= m_entries.size())
    return std::nullopt;
  const TEntry& e = m_entries[m_next];
  TRGBDFrame f;
  f.index = m_next;
  // The colour image's own time; the depth image keeps its stamp (it has its
  // own, and the description says nothing of its latency).
  f.timestamp = e.time;
  f.depthTimestamp = e.depthStamp;
  const TSensorDescription& sensor = m_sensor.sensor;
  std::tie(f.rgb, f.depth) = readRawFrame(e);
  if (!sensor.depth_registered)
    f.depth = registerDepthToColour(f.depth, m_depthCamera, m_camera, sensor.depth_pose_in_colour);
  f.camera = m_camera;
  f.rgbSource = e.rgbFile;
  ++m_next;
  return f;
}

std::optional<std::string> CTumFrameSource::groundTruthFile() const
{
  if (!m_groundTruthTemp.empty())
    return m_groundTruthTemp;
  const fs::path gt = fs::path(m_dir) / "groundtruth.txt";
  if (fs::is_regular_file(gt))
    return gt.string();
  return std::nullopt;
}

std::optional<std::string> CTumFrameSource::accelerometerFile() const
{
  const fs::path file = fs::path(m_dir) / "accelerometer.txt";
  if (fs::is_regular_file(file))
    return file.string();
  return std::nullopt;
}

std::string CTumFrameSource::name() const
{
  return fs::path(m_dir).filename().string();
}
}  // namespace roislam::io
