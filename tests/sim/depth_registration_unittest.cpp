// Unregistered depth (a 7-Scenes-like sensor: depth from its own camera, a
// known extrinsic) read back through the TUM reader and the sensor
// description that rgbd-simul writes is registered to the colour camera:
// against the same frames rendered with registered depth, the points agree
// within a centimetre at about 2 m.
#include <gtest/gtest.h>
#include <roislam/io/CFrameSource.h>
#include <roislam/sim/CRgbdSimulator.h>
#include <roislam/testing/TestData.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <vector>

namespace fs = std::filesystem;
using roislam::sim::CRgbdSimulator;

namespace
{
constexpr std::size_t kFrames = 3;

CRgbdSimulator::TOptions options(bool registered)
{
  CRgbdSimulator::TOptions o;
  o.scene = "textured";
  o.noise = false;
  o.frames = kFrames;
  o.rollingShutterMs = 0;  // both renderings see each frame from one pose
  o.depthRegistered = registered;
  o.depthFx = o.depthFy = 575.8;
  o.depthCx = 322.0;
  o.depthCy = 236.0;
  // A Kinect's IR camera: 2.5 cm baseline, slightly turned.
  o.depthPoseInColour = "[-0.025 0.002 0.001 0.8 -0.5 0.3]";
  return o;
}

/** 3-D point errors (m) between two depth images on the colour grid, where
 *  both read 1.5..2.5 m and the reference is smooth (3x3 span < 2 cm). */
std::vector<double> pointErrors(
    const cv::Mat& depth, const cv::Mat& reference, const mrpt::img::TCamera& cam)
{
  std::vector<double> err;
  for (int v = 1; v < reference.rows - 1; ++v)
    for (int u = 1; u < reference.cols - 1; ++u)
    {
      const float z = depth.at<float>(v, u), zr = reference.at<float>(v, u);
      if (!(z > 0) || zr < 1.5f || zr > 2.5f)
        continue;
      double lo = zr, hi = zr;
      for (int dv = -1; dv <= 1; ++dv)
        for (int du = -1; du <= 1; ++du)
        {
          const double n = reference.at<float>(v + dv, u + du);
          lo = std::min(lo, n);
          hi = std::max(hi, n);
        }
      if (hi - lo > 0.02)
        continue;
      const double x = (u - cam.cx()) / cam.fx(), y = (v - cam.cy()) / cam.fy();
      err.push_back(std::abs(z - zr) * std::sqrt(1 + x * x + y * y));
    }
  return err;
}

double quantile(std::vector<double> v, double q)
{
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * (v.size() - 1))];
}
}  // namespace

TEST(DepthRegistration, UnregisteredSyntheticDepthIsRegisteredWithinACentimetreAt2m)
{
  const fs::path dir = roislam::testing::makeTempDir("unregistered");
  const fs::path seq = dir / "seq";
  std::vector<cv::Mat> raw;
  {
    CRgbdSimulator sim(options(false));
    sim.writeSequence(seq.string());
    for (std::size_t i = 0; i < kFrames; ++i)
      raw.push_back(sim.renderFrame(i).depth);
  }
  std::vector<CRgbdSimulator::TFrame> truth;
  {
    CRgbdSimulator sim(options(true));
    for (std::size_t i = 0; i < kFrames; ++i)
      truth.push_back(sim.renderFrame(i));
  }

  // The folder's camera.ini says the depth is not registered; the reader registers it.
  auto source = roislam::io::CFrameSource::open(seq.string(), "auto");
  EXPECT_FALSE(source->sensor().sensor.depth_registered);
  EXPECT_NE(source->sensor().reason.find("camera.ini"), std::string::npos);
  ASSERT_EQ(source->size(), kFrames);
  std::vector<double> registered, unregistered;
  for (std::size_t i = 0; i < kFrames; ++i)
  {
    const auto f = source->next();
    ASSERT_TRUE(f);
    const auto cam = f->camera;
    const auto e = pointErrors(f->depth, truth[i].depth, cam);
    registered.insert(registered.end(), e.begin(), e.end());
    // Control: the depth camera's image taken as if it were registered.
    const auto c = pointErrors(raw[i], truth[i].depth, cam);
    unregistered.insert(unregistered.end(), c.begin(), c.end());
  }
  ASSERT_GT(registered.size(), 10000u);
  const double median = quantile(registered, 0.5), p95 = quantile(registered, 0.95);
  std::cout << "registered point error at 1.5-2.5 m: median " << median * 1000 << " mm, 95% "
            << p95 * 1000 << " mm over " << registered.size() << " pixels; unregistered 95% "
            << quantile(unregistered, 0.95) * 1000 << " mm\n";
  EXPECT_LT(p95, 0.01);
  EXPECT_LT(median, 0.003);
  EXPECT_GT(quantile(unregistered, 0.95), 0.01);
  fs::remove_all(dir);
}
