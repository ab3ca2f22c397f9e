// CRgbdSimulator::writeSequence: the rendered frames written as a TUM RGB-D
// folder (images, lists, ground truth, accelerometer, camera.ini and
// simulator.ini), complete or absent. Rendering is in CRgbdSimulator.cpp.
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/math/CMatrixFixed.h>
#include <mrpt/random/RandomGenerators.h>
#include <roislam/common/COutputFolder.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <stdexcept>
#include <string>

#include "roislam/io/TumAccelerometer.h"
#include "roislam/io/TumTrajectory.h"
#include "roislam/sim/CRgbdSimulator.h"

namespace fs = std::filesystem;

namespace roislam::sim
{
namespace
{
std::string stampName(double t)
{
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.6f", t);
  return buf;
}

void writeTextFile(const fs::path& file, const std::string& content)
{
  std::ofstream f(file);
  f << content;
  f.close();
  if (!f)
    throw std::runtime_error("cannot write " + file.string());
}

void writePng(const fs::path& file, const cv::Mat& img)
{
  bool ok = false;
  try
  {
    // OpenCV's default PNG settings measured fastest here (about 10 ms per
    // noisy 640x480 colour image; explicit level 1 took 25 ms).
    ok = cv::imwrite(file.string(), img);
  }
  catch (const cv::Exception& e)
  {
    throw std::runtime_error("cannot write " + file.string() + ": " + e.what());
  }
  if (!ok)
    throw std::runtime_error("cannot write " + file.string());
}
}  // namespace

namespace
{
// ------------------------------------------------------- writeSequence stages

roislam::common::COutputFolder::TOptions sequenceFolderOptions(bool overwrite)
{
  roislam::common::COutputFolder::TOptions folderOptions;
  folderOptions.overwrite = overwrite;
  folderOptions.known = {"rgb",        "depth",         "rgb.txt",         "depth.txt",
                         "camera.ini", "simulator.ini", "groundtruth.txt", "accelerometer.txt"};
  folderOptions.knownPrefixes = {"frame-"};  // layout 7scenes
  return folderOptions;
}

/** 7-Scenes' file stem of frame i: frame-NNNNNN. */
std::string sevenScenesStem(std::size_t i)
{
  char buf[32];
  std::snprintf(buf, sizeof buf, "frame-%06zu", i);
  return buf;
}

/** One frame in 7-Scenes' layout: colour, depth in mm with 65535 where there
 *  is no reading, and the 4x4 pose of the camera the depth comes from. */
void writeSevenScenesFrame(
    const fs::path& tmp, const CRgbdSimulator::TFrame& f, const mrpt::poses::CPose3D& depthPose,
    cv::Mat& depth16)
{
  const std::string stem = sevenScenesStem(f.index);
  f.depth.convertTo(depth16, CV_16UC1, 1000.0);  // max_depth <= 13.1 m: no overflow
  depth16.setTo(0xFFFF, f.depth <= 0);
  writePng(tmp / (stem + ".color.png"), f.rgb);
  writePng(tmp / (stem + ".depth.png"), depth16);
  const auto H = depthPose.getHomogeneousMatrixVal<mrpt::math::CMatrixDouble44>();
  std::ostringstream pose;
  pose.precision(17);
  for (int r = 0; r < 4; ++r)
    pose << H(r, 0) << '\t' << H(r, 1) << '\t' << H(r, 2) << '\t' << H(r, 3) << "\t\n";
  writeTextFile(tmp / (stem + ".pose.txt"), pose.str());
}

void createImageFolders(const fs::path& tmp)
{
  std::error_code ec;
  fs::create_directories(tmp / "rgb", ec);
  if (!ec)
    fs::create_directories(tmp / "depth", ec);
  if (ec)
    throw std::runtime_error("cannot write to " + tmp.string() + ": " + ec.message());
}

/** What the sequence's lists and logs accumulate frame by frame, written once
 *  all frames are out. */
struct TSequenceLogs
{
  std::ostringstream rgbTxt, depthTxt;
  roislam::io::TTrajectory gt;
  roislam::io::TAccelerometerLog accelerometer;
};

std::string sequenceDescription(const CRgbdSimulator::TOptions& o)
{
  return "rgbd-simul scene " + o.scene + " seed " + std::to_string(o.seed) +
         (o.noise ? "" : " no-noise");
}

void writeListHeaders(const std::string& desc, TSequenceLogs& logs)
{
  logs.rgbTxt << "# color images\n# file: '" << desc << "'\n# timestamp filename\n";
  logs.depthTxt << "# depth maps\n# file: '" << desc << "'\n# timestamp filename\n";
}

/** Writes the frame's two PNGs and lists them, stamped `delay` seconds after
 *  the images were taken (stamp_delay); depth16 is reused scratch. */
void writeFrameImages(
    const fs::path& tmp, const CRgbdSimulator::TFrame& f, double delay, cv::Mat& depth16,
    TSequenceLogs& logs)
{
  const std::string rgbStamp = stampName(f.timestamp + delay);
  const std::string depthStamp = stampName(f.depthTimestamp + delay);
  const std::string rgbName = "rgb/" + rgbStamp + ".png";
  const std::string depthName = "depth/" + depthStamp + ".png";
  // Round to the nearest 1/5000 m; beyond 13.1 m cannot occur (max_depth).
  f.depth.convertTo(depth16, CV_16UC1, CRgbdSimulator::kDepthScale);
  writePng(tmp / rgbName, f.rgb);
  writePng(tmp / depthName, depth16);
  logs.rgbTxt << rgbStamp << ' ' << rgbName << '\n';
  logs.depthTxt << depthStamp << ' ' << depthName << '\n';
}

/** The accelerometer reading as published: in the output axes, with noise. */
mrpt::math::TVector3D publishedAccelerometer(
    mrpt::math::TVector3D reading, const CRgbdSimulator::TOptions& o,
    mrpt::random::CRandomGenerator& accelRng)
{
  if (o.cameraYUp)
    reading.y = -reading.y;  // the Kinect axes are a half turn about the optical z
  if (o.noise)
    reading += mrpt::math::TVector3D(
        accelRng.drawGaussian1D(0, 0.05), accelRng.drawGaussian1D(0, 0.05),
        accelRng.drawGaussian1D(0, 0.05));
  return reading;
}

void writeSequenceLogs(const fs::path& tmp, const std::string& desc, const TSequenceLogs& logs)
{
  writeTextFile(tmp / "rgb.txt", logs.rgbTxt.str());
  writeTextFile(tmp / "depth.txt", logs.depthTxt.str());
  roislam::io::saveTumTrajectory(
      (tmp / "groundtruth.txt").string(), logs.gt,
      "ground truth of " + desc + ": colour optical centre in the world");
  roislam::io::saveTumAccelerometer(
      (tmp / "accelerometer.txt").string(), logs.accelerometer,
      "accelerometer data of " + desc + " (TUM Kinect axes)");
}

void writeSimulatorSettings(const fs::path& tmp, const CRgbdSimulator& sim)
{
  mrpt::config::CConfigFileMemory simCfg;
  sim.options().saveToConfigFile(simCfg, "RgbdSimulator");
  writeTextFile(tmp / "simulator.ini", simCfg.getContent());
}

void writeSequenceSettings(const fs::path& tmp, const CRgbdSimulator& sim)
{
  writeTextFile(tmp / "camera.ini", sim.sensorDescription().toIniText());
  writeSimulatorSettings(tmp, sim);
}
}  // namespace

CRgbdSimulator::TWriteStats CRgbdSimulator::writeSequence(const std::string& outDir, bool overwrite)
{
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  // Complete or absent: a staging folder beside outDir, renamed at the end.
  roislam::common::COutputFolder folder(outDir, sequenceFolderOptions(overwrite));
  const fs::path tmp(folder.path());
  const bool sevenScenes = m_opts.layout == "7scenes";
  if (!sevenScenes)
    createImageFolders(tmp);

  TWriteStats st;
  try
  {
    const std::string desc = sequenceDescription(m_opts);
    TSequenceLogs logs;
    writeListHeaders(desc, logs);
    // Its own noise stream, so the images do not change with it.
    mrpt::random::CRandomGenerator accelRng(m_opts.seed * 2246822519u + 0x165667b1u);
    cv::Mat depth16;
    for (std::size_t i = 0; i < m_opts.frames; ++i)
    {
      const auto r0 = Clock::now();
      const TFrame f = renderFrame(i);
      const auto r1 = Clock::now();
      if (sevenScenes)
      {
        writeSevenScenesFrame(
            tmp, f, m_opts.depthRegistered ? f.pose : f.pose + depthPoseInColour(), depth16);
        st.writeSeconds += std::chrono::duration<double>(Clock::now() - r1).count();
        st.renderSeconds += std::chrono::duration<double>(r1 - r0).count();
        continue;
      }
      writeFrameImages(tmp, f, m_opts.stampDelay, depth16, logs);
      logs.gt.push_back({f.timestamp, published(f.pose)});
      logs.accelerometer.push_back(
          {f.timestamp, publishedAccelerometer(accelerometerReading(i), m_opts, accelRng)});
      st.renderSeconds += std::chrono::duration<double>(r1 - r0).count();
      st.writeSeconds += std::chrono::duration<double>(Clock::now() - r1).count();
      MRPT_LOG_DEBUG_STREAM("frame " << i << " written");
    }
    st.frames = m_opts.frames;
    if (sevenScenes)
      writeSimulatorSettings(tmp, *this);
    else
    {
      writeSequenceLogs(tmp, desc, logs);
      writeSequenceSettings(tmp, *this);
    }

    folder.commit();
  }
  catch (const fs::filesystem_error& e)
  {
    throw std::runtime_error("cannot write " + outDir + ": " + e.what());
  }
  st.totalSeconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return st;
}
}  // namespace roislam::sim
