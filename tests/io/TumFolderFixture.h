/* Builds small TUM-layout folders in a temporary directory for the io tests:
 * rgb/ and depth/ PNGs with known content plus rgb.txt/depth.txt; and the
 * check of the one-line error messages the io layer promises.
 */
#pragma once

#include <gtest/gtest.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/img/TCamera.h>
#include <roislam/testing/TestData.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace roislam::iotest
{
/** Expects fn to throw an exception whose one-line message contains part. */
template <typename F>
void expectError(F&& fn, const std::string& part)
{
  try
  {
    fn();
    ADD_FAILURE() << "no exception, expected one mentioning '" << part << "'";
  }
  catch (const std::exception& e)
  {
    const std::string what = e.what();
    EXPECT_NE(what.find(part), std::string::npos) << "message: " << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << "not one line: " << what;
  }
}

/** Small pinhole camera for synthetic folders (W x H pixels). */
inline mrpt::img::TCamera smallCamera(int w = 16, int h = 12)
{
  mrpt::img::TCamera c;
  c.ncols = static_cast<uint32_t>(w);
  c.nrows = static_cast<uint32_t>(h);
  c.setIntrinsicParamsFromValues(20.0, 21.0, 7.5, 5.5);
  return c;
}

/** Deterministic colour image, different per frame. */
inline cv::Mat colourImage(int w, int h, int seed)
{
  cv::Mat img(h, w, CV_8UC3);
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c)
      img.at<cv::Vec3b>(r, c) = cv::Vec3b(
          static_cast<uint8_t>((r * 31 + c * 7 + seed * 13) % 256),
          static_cast<uint8_t>((r * 3 + c * 17 + seed * 29) % 256),
          static_cast<uint8_t>((r * 11 + c * 5 + seed * 71) % 256));
  return img;
}

/** Deterministic raw 16-bit depth, with some zero (invalid) pixels. */
inline cv::Mat depthImage(int w, int h, int seed)
{
  cv::Mat img(h, w, CV_16UC1);
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c)
      img.at<uint16_t>(r, c) =
          ((r + c + seed) % 9 == 0) ? 0 : static_cast<uint16_t>(5000 + 37 * r + 113 * c + seed);
  return img;
}

inline std::string stampText(double t)
{
  std::ostringstream ss;
  ss << std::fixed << std::setprecision(6) << t;
  return ss.str();
}

/** Writes a TUM folder <root>/<name> with the given colour and depth stamps;
 *  returns its path. Images are colourImage(i)/depthImage(j) by list index. */
inline std::string writeTumFolder(
    const std::string& root, const std::string& name, const std::vector<double>& rgbStamps,
    const std::vector<double>& depthStamps, int w = 16, int h = 12)
{
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(root) / name;
  fs::create_directories(dir / "rgb");
  fs::create_directories(dir / "depth");
  std::ofstream rgbList(dir / "rgb.txt"), depthList(dir / "depth.txt");
  rgbList << "# color images\n# timestamp filename\n";
  depthList << "# depth maps\n# timestamp filename\n";
  for (std::size_t i = 0; i < rgbStamps.size(); ++i)
  {
    const std::string f = "rgb/" + stampText(rgbStamps[i]) + ".png";
    cv::imwrite((dir / f).string(), colourImage(w, h, static_cast<int>(i)));
    rgbList << stampText(rgbStamps[i]) << " " << f << "\n";
  }
  for (std::size_t j = 0; j < depthStamps.size(); ++j)
  {
    const std::string f = "depth/" + stampText(depthStamps[j]) + ".png";
    cv::imwrite((dir / f).string(), depthImage(w, h, static_cast<int>(j)));
    depthList << stampText(depthStamps[j]) << " " << f << "\n";
  }
  return dir.string();
}

/** Writes a calibration file exactly as TCamera::saveToConfigFile does
 *  (section [CAMERA_PARAMS]), which is what rgbd-simul writes as camera.ini. */
inline void writeCameraIni(const std::string& file, const mrpt::img::TCamera& cam)
{
  mrpt::config::CConfigFile cfg(file);
  cam.saveToConfigFile("CAMERA_PARAMS", cfg);
  cfg.writeNow();
}
}  // namespace roislam::iotest
