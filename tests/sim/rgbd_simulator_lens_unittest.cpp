// CRgbdSimulator's colour lens (colour_dist): the rendered image against
// the pinhole render resampled through OpenCV's own undistortion.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <roislam/sim/CRgbdSimulator.h>

#include <cmath>
#include <cstdio>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

using roislam::sim::CRgbdSimulator;

namespace
{
CRgbdSimulator::TOptions noiseFreeGlobalShutter()
{
  CRgbdSimulator::TOptions o;
  o.scene = "textured";
  o.noise = false;
  o.frames = 10;
  o.rollingShutterMs = 0;
  return o;
}
}  // namespace

// A distorted colour image is the pinhole image seen through the lens:
// resampled at OpenCV's own undistortion of each pixel (an implementation
// the simulator does not use), the pinhole render gives it back. Registered
// depth lies on the distorted grid alike. Pincushion (the TUM fr1 Kinect's
// colour lens) and barrel (a zoomed-out pinhole render behind it).
TEST(RgbdSimulatorLens, DistortedImageIsTheLensOverThePinhole)
{
  for (const char* dist : {"[0.2624 -0.9531 -0.0054 0.0026 1.1633]", "[-0.25 0.08 0 0 0]"})
  {
    SCOPED_TRACE(dist);
    auto o = noiseFreeGlobalShutter();
    const auto plain = CRgbdSimulator(o).renderFrame(5);
    o.colourDist = dist;
    CRgbdSimulator sim(o);
    const auto f = sim.renderFrame(5);
    const auto cam = sim.camera();
    cv::Mat K = (cv::Mat_<double>(3, 3) << cam.fx(), 0, cam.cx(), 0, cam.fy(), cam.cy(), 0, 0, 1);
    cv::Mat D(1, 5, CV_64F);
    for (int k = 0; k < 5; ++k)
      D.at<double>(k) = cam.dist[k];
    std::vector<cv::Point2f> pix, undist;
    for (int v = 0; v < f.rgb.rows; ++v)
      for (int u = 0; u < f.rgb.cols; ++u)
        pix.emplace_back(float(u), float(v));
    cv::undistortPoints(
        pix, undist, K, D, cv::noArray(), K,
        cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 50, 1e-9));
    cv::Mat mapX(f.rgb.size(), CV_32FC1), mapY(f.rgb.size(), CV_32FC1);
    for (std::size_t k = 0; k < pix.size(); ++k)
    {
      mapX.at<float>(int(pix[k].y), int(pix[k].x)) = undist[k].x;
      mapY.at<float>(int(pix[k].y), int(pix[k].x)) = undist[k].y;
    }
    cv::Mat expected, depthExpected;
    cv::remap(plain.rgb, expected, mapX, mapY, cv::INTER_LINEAR, cv::BORDER_CONSTANT);
    cv::remap(plain.depth, depthExpected, mapX, mapY, cv::INTER_NEAREST, cv::BORDER_CONSTANT);
    // Compared where the pinhole render reaches (barrel: not the corners).
    cv::Mat inside =
        (mapX >= 1) & (mapX <= f.rgb.cols - 2) & (mapY >= 1) & (mapY <= f.rgb.rows - 2);
    cv::Mat diff;
    cv::absdiff(f.rgb, expected, diff);
    const double err = cv::mean(diff, inside)[1];
    cv::absdiff(f.rgb, plain.rgb, diff);
    const double unmoved = cv::mean(diff, inside)[1];
    std::printf(
        "%s: colour %.2f grey levels (%.2f against the pinhole image)\n", dist, err, unmoved);
    EXPECT_LT(err, 2.0);
    EXPECT_GT(unmoved, 4 * err);
    // The lens sees everything it shows: no corner is left without content.
    cv::Mat grey;
    cv::cvtColor(f.rgb, grey, cv::COLOR_BGR2GRAY);
    for (const cv::Point c :
         {cv::Point(2, 2), cv::Point(637, 2), cv::Point(2, 477), cv::Point(637, 477)})
      EXPECT_GT(grey.at<uchar>(c), 0) << c;
    // Depth: the same surface point within a millimetre where both agree
    // it is smooth (the nearest pinhole pixel is up to half a pixel off).
    int compared = 0, close = 0;
    for (int v = 8; v < 472; v += 5)
      for (int u = 8; u < 632; u += 5)
      {
        const float z = f.depth.at<float>(v, u), ze = depthExpected.at<float>(v, u);
        if (!inside.at<uchar>(v, u) || z <= 0 || ze <= 0)
          continue;
        ++compared;
        close += std::abs(z - ze) < 0.001 + 0.01 * ze;
      }
    EXPECT_GT(compared, 8000);
    EXPECT_GT(close, 0.98 * compared);
    EXPECT_EQ(sim.sensorDescription().colour.dist[0], cam.dist[0]);
  }
}

// colour_dist round-trips through the options and into the camera the
// sequence's camera.ini describes, with its distortion model.
TEST(RgbdSimulatorLens, RoundTripsIntoTheCameraItDescribes)
{
  mrpt::config::CConfigFileMemory lens;
  lens.write("RgbdSimulator", "colour_dist", "[0.2624 -0.9531 -0.0054 0.0026 1.1633]");
  CRgbdSimulator::TOptions x;
  x.loadFromConfigFile(lens, "RgbdSimulator");
  mrpt::config::CConfigFileMemory again;
  x.saveToConfigFile(again, "S");
  CRgbdSimulator::TOptions y;
  y.loadFromConfigFile(again, "S");
  const auto cam = CRgbdSimulator(y).sensorDescription().colour;
  EXPECT_DOUBLE_EQ(cam.dist[0], 0.2624);
  EXPECT_DOUBLE_EQ(cam.dist[4], 1.1633);
  EXPECT_EQ(cam.distortion, mrpt::img::DistortionModel::plumb_bob);
}
