// CRgbdSimulator: rendered frames against the analytic scene, noise,
// determinism, options and the written TUM layout.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <roislam/io/CFrameSource.h>
#include <roislam/io/CTumFrameSource.h>
#include <roislam/io/CameraPresets.h>
#include <roislam/io/TumAccelerometer.h>
#include <roislam/io/TumTrajectory.h>
#include <roislam/sim/CRgbdSimulator.h>
#include <roislam/testing/TestData.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <string>

namespace fs = std::filesystem;
using roislam::sim::CRgbdSimulator;

namespace
{
CRgbdSimulator::TOptions opts(const std::string& scene, bool noise, unsigned frames = 10)
{
  CRgbdSimulator::TOptions o;
  o.scene = scene;
  o.noise = noise;
  o.frames = frames;
  // The analytic checks compare every row with the frame's one pose.
  o.rollingShutterMs = 0;
  return o;
}

struct TDepthCheck
{
  int compared = 0, depthOk = 0, surfaceOk = 0;
};

/** Compares the rendered depth of a noise-free frame with the analytic scene on
 *  a pixel grid, away from depth discontinuities; rowPose(v) is the camera
 *  pose row v was rendered from (default: the frame's, carried to the depth
 *  camera); cam the depth camera (default: the simulator's). */
TDepthCheck checkDepth(
    const CRgbdSimulator& sim, const CRgbdSimulator::TFrame& frame,
    const std::function<mrpt::poses::CPose3D(int)>& rowPose = {},
    std::optional<mrpt::img::TCamera> camera = std::nullopt)
{
  const auto cam = camera ? *camera : sim.depthCamera();
  TDepthCheck res;
  CRgbdSimulator::TFrame f = frame;
  f.pose = f.pose + sim.depthPoseInColour();
  for (int v = 4; v < f.depth.rows - 4; v += 7)
    for (int u = 4; u < f.depth.cols - 4; u += 7)
    {
      if (rowPose)
        f.pose = rowPose(v);
      const float z = f.depth.at<float>(v, u);
      const auto za = sim.scene().depthAt(f.pose, cam, u, v);
      if (z <= 0 || !za)
        continue;
      bool smooth = true;  // all 3x3 neighbours on the same surface nearby
      for (int dv = -1; dv <= 1; ++dv)
        for (int du = -1; du <= 1; ++du)
        {
          const auto zn = sim.scene().depthAt(f.pose, cam, u + du, v + dv);
          smooth = smooth && zn && std::abs(*zn - *za) < 0.01 * *za;
        }
      if (!smooth)
        continue;
      ++res.compared;
      if (std::abs(z - *za) < 0.0005)
        ++res.depthOk;
      // Unproject with the intrinsics and the ground-truth pose.
      const mrpt::math::TPoint3D pc(
          (u - cam.cx()) * z / cam.fx(), (v - cam.cy()) * z / cam.fy(), z);
      const auto pw = f.pose.composePoint(pc);
      if (sim.scene().distanceToSurface(pw) < 0.002)
        ++res.surfaceOk;
    }
  return res;
}

double gradientAbove(const cv::Mat& bgr, double thr)
{
  cv::Mat g, gx, gy, mag;
  cv::cvtColor(bgr, g, cv::COLOR_BGR2GRAY);
  cv::Sobel(g, gx, CV_32F, 1, 0);
  cv::Sobel(g, gy, CV_32F, 0, 1);
  cv::magnitude(gx, gy, mag);
  return cv::countNonZero(mag > thr) / static_cast<double>(mag.total());
}

int orbCount(const cv::Mat& bgr)
{
  cv::Mat g;
  cv::cvtColor(bgr, g, cv::COLOR_BGR2GRAY);
  std::vector<cv::KeyPoint> kps;
  cv::ORB::create(1000)->detect(g, kps);
  return static_cast<int>(kps.size());
}

std::size_t countLines(const fs::path& p)
{
  std::ifstream f(p);
  std::string l;
  std::size_t n = 0;
  while (std::getline(f, l))
    if (!l.empty() && l[0] != '#')
      ++n;
  return n;
}
}  // namespace

TEST(RgbdSimulator, TexturedDepthMatchesGeometryExactly)
{
  CRgbdSimulator sim(opts("textured", false));
  for (std::size_t i : {0, 6})
  {
    const auto f = sim.renderFrame(i);
    ASSERT_EQ(f.depth.cols, 640);
    ASSERT_EQ(f.depth.rows, 480);
    const auto r = checkDepth(sim, f);
    EXPECT_GT(r.compared, 3000) << "frame " << i;
    EXPECT_GE(r.depthOk, r.compared * 0.995) << "frame " << i;
    EXPECT_GE(r.surfaceOk, r.compared * 0.995) << "frame " << i;
    // Kinect range: everything in the room is within 0.4-4 m from the path.
    EXPECT_GT(cv::countNonZero(f.depth > 0), 0.99 * f.depth.total());
  }
}

TEST(RgbdSimulator, FurnishedDepthMatchesGeometryExactly)
{
  cv::Mat bareDepth;
  {
    // One rendering simulator per thread at a time.
    CRgbdSimulator bare(opts("textured", false));
    bareDepth = bare.renderFrame(0).depth;
  }
  auto o = opts("textured", false);
  o.furniture = true;
  CRgbdSimulator sim(o);
  for (std::size_t i : {0, 6})
  {
    const auto f = sim.renderFrame(i);
    const auto r = checkDepth(sim, f);
    EXPECT_GT(r.compared, 3000) << "frame " << i;
    EXPECT_GE(r.depthOk, r.compared * 0.995) << "frame " << i;
    EXPECT_GE(r.surfaceOk, r.compared * 0.995) << "frame " << i;
  }
  // The furniture is in view and nearer than the bare room there.
  const cv::Mat depth = sim.renderFrame(0).depth;
  const cv::Mat nearer = depth < bareDepth - 0.05F;
  EXPECT_GT(cv::countNonZero(nearer), 0.1 * depth.total());
}

TEST(RgbdSimulator, RollingShutterRowsSeeTheScenesFromTheirOwnTime)
{
  auto o = opts("textured", false);
  o.rollingShutterMs = 25;
  CRgbdSimulator sim(o);
  ASSERT_EQ(sim.bandHeight(), 8u);
  const std::size_t i = 6;  // the path turns at tens of deg/s here
  const auto f = sim.renderFrame(i);
  // Ground truth stays the middle row's pose, at the frame's stamp.
  EXPECT_EQ(f.pose, sim.groundTruthPose(i));
  auto rowPose = [&](int v)
  {
    const double yMid = (v / 8) * 8 + 3.5;
    return sim.path().opticalPoseAt(i / o.fps + (yMid / o.height - 0.5) * 0.025);
  };
  const auto own = checkDepth(sim, f, rowPose);
  EXPECT_GT(own.compared, 3000);
  EXPECT_GE(own.depthOk, own.compared * 0.995);
  EXPECT_GE(own.surfaceOk, own.compared * 0.995);
  // Read with the one middle-row pose, the rows away from the middle are off.
  const auto one = checkDepth(sim, f);
  EXPECT_LT(one.surfaceOk, own.surfaceOk * 0.8);
}

TEST(RgbdSimulator, CommonShiftMovesTheColourImageOnly)
{
  auto o = opts("textured", false);
  o.rollingShutterMs = 0;
  const auto plain = CRgbdSimulator(o).renderFrame(5);
  o.commonShiftPx = 1.5;
  CRgbdSimulator sim(o);
  const auto f = sim.renderFrame(5);
  EXPECT_GT(cv::norm(f.colourShiftPx), 0.05);
  EXPECT_EQ(sim.renderFrame(5).colourShiftPx, f.colourShiftPx);  // one draw per (seed, frame)
  EXPECT_NE(sim.renderFrame(6).colourShiftPx, f.colourShiftPx);
  // The colour content moved by the drawn shift (phase correlation of the
  // two renders), the depth did not move at all.
  cv::Mat a, b;
  cv::cvtColor(plain.rgb, a, cv::COLOR_BGR2GRAY);
  cv::cvtColor(f.rgb, b, cv::COLOR_BGR2GRAY);
  a.convertTo(a, CV_64F);
  b.convertTo(b, CV_64F);
  const cv::Point2d moved = cv::phaseCorrelate(a, b);
  EXPECT_NEAR(moved.x, f.colourShiftPx.x, 0.25);
  EXPECT_NEAR(moved.y, f.colourShiftPx.y, 0.25);
  EXPECT_EQ(cv::norm(plain.depth, f.depth, cv::NORM_INF), 0.0);
  EXPECT_EQ(plain.colourShiftPx, cv::Point2d());
}

TEST(RgbdSimulator, ExposureBlursTheColourAlongTheMotionOnly)
{
  auto o = opts("textured", false);
  const auto plain = CRgbdSimulator(o).renderFrame(5);
  o.exposureMs = 25;
  CRgbdSimulator sim(o);
  const auto f = sim.renderFrame(5);
  // The colour is smeared: less fine detail (variance of the Laplacian), the
  // same mean brightness; the depth is the middle render's, unchanged.
  auto detail = [](const cv::Mat& bgr)
  {
    cv::Mat g, l;
    cv::cvtColor(bgr, g, cv::COLOR_BGR2GRAY);
    cv::Laplacian(g, l, CV_64F);
    cv::Scalar mean, sd;
    cv::meanStdDev(l, mean, sd);
    return sd[0] * sd[0];
  };
  EXPECT_LT(detail(f.rgb), 0.8 * detail(plain.rgb));
  EXPECT_NEAR(cv::mean(f.rgb)[1], cv::mean(plain.rgb)[1], 2.0);
  EXPECT_EQ(cv::norm(plain.depth, f.depth, cv::NORM_INF), 0.0);
  // Blur alone adds no keypoint timing noise to the camera it describes
  // (CRgbdSimulator.h).
  EXPECT_DOUBLE_EQ(sim.sensorDescription().keypoint_time_sigma_ms, 0);
}

TEST(RgbdSimulator, UnregisteredDepthIsTheDepthCamerasView)
{
  auto o = opts("textured", false);
  o.depthRegistered = false;
  o.depthFx = o.depthFy = 575.8;
  o.depthCx = 322.0;
  o.depthCy = 236.0;
  // 2.5 cm baseline and a slight misalignment, as a Kinect's IR camera has.
  o.depthPoseInColour = "[-0.025 0.002 0.001 0.8 -0.5 0.3]";
  CRgbdSimulator sim(o);
  const auto f = sim.renderFrame(4);
  EXPECT_DOUBLE_EQ(sim.depthCamera().fx(), 575.8);
  EXPECT_NEAR(sim.depthPoseInColour().x(), -0.025, 1e-12);
  const auto own = checkDepth(sim, f);
  EXPECT_GT(own.compared, 3000);
  EXPECT_GE(own.depthOk, own.compared * 0.995);
  EXPECT_GE(own.surfaceOk, own.compared * 0.995);
  // Read as if it were registered (colour camera, colour pose), it is not.
  const auto asRegistered = checkDepth(
      sim, f, [&](int) { return f.pose; }, sim.camera());
  EXPECT_LT(asRegistered.depthOk, own.depthOk * 0.5);
}

TEST(RgbdSimulator, RadialDepthBiasIsFixedInTheImage)
{
  // depth_radial_bias c: each reading is z (1 + c r^2) in the normalised
  // coordinates of the grid the depth lies on (the colour camera's when
  // registered, the depth camera's when not); c = 0 changes nothing.
  for (const bool registered : {true, false})
  {
    SCOPED_TRACE(registered ? "registered" : "unregistered");
    auto o = opts("textured", false);
    o.depthRegistered = registered;
    o.depthCx = 322.0;
    o.depthCy = 236.0;
    cv::Mat clean, biased;
    {
      CRgbdSimulator sim(o);
      clean = sim.renderFrame(4).depth;
    }
    o.depthRadialBias = 0.03;
    CRgbdSimulator sim(o);
    biased = sim.renderFrame(4).depth;
    const auto cam = registered ? sim.camera() : sim.depthCamera();
    int compared = 0;
    double worstCorner = 0;
    for (int v = 0; v < clean.rows; v += 3)
      for (int u = 0; u < clean.cols; u += 3)
      {
        const float z0 = clean.at<float>(v, u), z = biased.at<float>(v, u);
        if (!(z0 > 0) || !(z > 0))
          continue;
        const double x = (u - cam.cx()) / cam.fx(), y = (v - cam.cy()) / cam.fy();
        ASSERT_NEAR(z / z0, 1 + 0.03 * (x * x + y * y), 1e-6) << u << ", " << v;
        ++compared;
        worstCorner = std::max(worstCorner, static_cast<double>(z / z0) - 1);
      }
    EXPECT_GT(compared, 30000);
    // About 1.8 % at the corners (r^2 about 0.6 at 517 px, 0.5 at the depth
    // camera's 576 px).
    EXPECT_GT(worstCorner, 0.014);
    EXPECT_LT(worstCorner, 0.02);
  }
}

TEST(RgbdSimulator, DisparityNoiseModelIsSelectable)
{
  auto o = opts("textured", true);
  o.noiseModel = "disparity";
  auto clean = o;
  clean.noise = false;
  CRgbdSimulator::TFrame f, g;
  roislam::io::TSensorDescription noisy, noiseFree;
  {  // one rendering simulator per thread at a time
    CRgbdSimulator sim(o);
    f = sim.renderFrame(3);
    noisy = sim.sensorDescription();
  }
  {
    CRgbdSimulator sim(clean);
    g = sim.renderFrame(3);
    noiseFree = sim.sensorDescription();
  }
  // Every noisy reading is a quantised disparity: bf * steps / k for an integer k.
  int checked = 0, onGrid = 0;
  double sumSq = 0;
  int nDiff = 0;
  for (int v = 10; v < f.depth.rows - 10; v += 5)
    for (int u = 10; u < f.depth.cols - 10; u += 5)
    {
      const float z = f.depth.at<float>(v, u), z0 = g.depth.at<float>(v, u);
      if (!(z > 0) || !(z0 > 0))
        continue;
      const double k = o.disparityBf * o.disparityStepsPerPx / z;
      ++checked;
      onGrid += std::abs(k - std::round(k)) < 1e-3 * k ? 1 : 0;
      if (std::abs(z - z0) < 0.05 * z0)
      {
        sumSq += (z - z0) * (z - z0) / (z0 * z0 * z0 * z0);
        ++nDiff;
      }
    }
  ASSERT_GT(checked, 3000);
  EXPECT_GT(onGrid, checked * 0.99);
  // Away from edges the error per z^2 follows the model's sigma(z) / z^2
  // (noise and quantisation in disparity), widened by the lateral jitter on
  // slanted surfaces: within a factor 2 of the model.
  const double perZ2 = std::sqrt(sumSq / nDiff);
  EXPECT_EQ(noisy.depth_noise.model, "disparity");
  const double model = noisy.depth_noise.sigma(1.0);
  EXPECT_GT(perZ2, 0.7 * model);
  EXPECT_LT(perZ2, 2.0 * model);
  EXPECT_EQ(noiseFree.depth_noise.model, "none");
}

TEST(RgbdSimulator, TexturedSceneIsRichFeaturelessIsFlat)
{
  cv::Mat texturedRgb, featurelessRgb;
  {
    CRgbdSimulator sim(opts("textured", false));
    texturedRgb = sim.renderFrame(3).rgb;
  }
  CRgbdSimulator sim(opts("featureless", false));
  const auto f = sim.renderFrame(3);
  featurelessRgb = f.rgb;

  EXPECT_GT(orbCount(texturedRgb), 800);
  EXPECT_LT(orbCount(featurelessRgb), 250);
  // Canny 250/300 (stage 1 of the ROI detector) fires on the textured scene only.
  cv::Mat g, e;
  cv::cvtColor(texturedRgb, g, cv::COLOR_BGR2GRAY);
  cv::Canny(g, e, 250, 300);
  EXPECT_GT(cv::countNonZero(e), 5000);
  cv::cvtColor(featurelessRgb, g, cv::COLOR_BGR2GRAY);
  cv::Canny(g, e, 250, 300);
  EXPECT_LT(cv::countNonZero(e), 50);

  // On the walls of the featureless scene, the colour gradient is zero away
  // from face boundaries.
  const auto cam = sim.camera();
  cv::Mat grey, gx, gy;
  cv::cvtColor(featurelessRgb, grey, cv::COLOR_BGR2GRAY);
  cv::Sobel(grey, gx, CV_32F, 1, 0);
  cv::Sobel(grey, gy, CV_32F, 0, 1);
  int wallPixels = 0, flat = 0;
  for (int v = 5; v < 475; v += 5)
    for (int u = 5; u < 635; u += 5)
    {
      bool sameWall = true;
      std::size_t rect = 0;
      for (int dv = -3; dv <= 3 && sameWall; dv += 3)
        for (int du = -3; du <= 3 && sameWall; du += 3)
        {
          const auto pose = f.pose;
          const auto R = pose.getRotationMatrix();
          const double dc[3] = {(u + du - cam.cx()) / cam.fx(), (v + dv - cam.cy()) / cam.fy(), 1};
          mrpt::math::TVector3D d(0, 0, 0);
          for (int k = 0; k < 3; ++k)
          {
            d.x += R(0, k) * dc[k];
            d.y += R(1, k) * dc[k];
            d.z += R(2, k) * dc[k];
          }
          const auto hit = sim.scene().raycast({pose.x(), pose.y(), pose.z()}, d);
          sameWall = hit && sim.scene().rects()[hit->rect].name.rfind("wall", 0) == 0 &&
                     (du == -3 && dv == -3 ? (rect = hit->rect, true) : hit->rect == rect);
        }
      if (!sameWall)
        continue;
      ++wallPixels;
      if (std::hypot(gx.at<float>(v, u), gy.at<float>(v, u)) < 1.0)
        ++flat;
    }
  EXPECT_GT(wallPixels, 500);
  EXPECT_EQ(flat, wallPixels);
  EXPECT_LT(gradientAbove(featurelessRgb, 20.0), 0.03);
}

TEST(RgbdSimulator, NoiseIsDeterministicPerSeedAndHasKinectSpread)
{
  cv::Mat clean, a, b, c;
  {
    CRgbdSimulator sim(opts("textured", false));
    clean = sim.renderFrame(4).depth;
  }
  auto noisy = [](uint32_t seed)
  {
    auto o = opts("textured", true);
    o.seed = seed;
    CRgbdSimulator sim(o);
    return sim.renderFrame(4);
  };
  const auto fa = noisy(3), fb = noisy(3), fc = noisy(4);
  EXPECT_EQ(cv::norm(fa.depth, fb.depth, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(fa.rgb, fb.rgb, cv::NORM_INF), 0.0);
  const cv::Mat bothValid = (fa.depth > 0) & (fc.depth > 0);
  EXPECT_GT(
      cv::countNonZero((fa.depth != fc.depth) & bothValid), 0.9 * cv::countNonZero(bothValid));

  // Residuals against the clean depth, normalised by the model sigma.
  double sum2 = 0;
  int n = 0, dropped = 0, valid = 0;
  for (int r = 0; r < clean.rows; ++r)
    for (int col = 0; col < clean.cols; ++col)
    {
      const float z0 = clean.at<float>(r, col), z = fa.depth.at<float>(r, col);
      if (z0 <= 0)
        continue;
      ++valid;
      if (z <= 0)
      {
        ++dropped;
        continue;
      }
      const double s = 0.0012 + 0.0019 * (z0 - 0.4) * (z0 - 0.4);
      sum2 += (z - z0) * (z - z0) / (s * s);
      ++n;
    }
  EXPECT_NEAR(std::sqrt(sum2 / n), 1.0, 0.05);
  // Edge dropout removes some, but not many, readings.
  EXPECT_GT(dropped, 500);
  EXPECT_LT(dropped, 0.1 * valid);
}

TEST(RgbdSimulator, OptionsLoadValidateAndRoundTrip)
{
  mrpt::config::CConfigFileMemory cfg;
  cfg.write("RgbdSimulator", "scene", "featureless");
  cfg.write("RgbdSimulator", "frames", "12");
  cfg.write("RgbdSimulator", "noise", "false");
  cfg.write("RgbdSimulator", "max_depth", "3.5");
  cfg.write("RgbdSimulator", "common_shift_px", "0.4");
  cfg.write("RgbdSimulator", "exposure_ms", "12.5");
  cfg.write("RgbdSimulator", "exposure_samples", "5");
  cfg.write("RgbdSimulator", "furniture", "true");
  cfg.write("RgbdSimulator", "depth_radial_bias", "-0.025");
  cfg.write("RgbdSimulator", "stamp_delay", "0.009");
  CRgbdSimulator::TOptions o;
  o.loadFromConfigFile(cfg, "RgbdSimulator");
  EXPECT_EQ(o.scene, "featureless");
  EXPECT_TRUE(o.furniture);
  EXPECT_EQ(o.frames, 12u);
  EXPECT_FALSE(o.noise);
  EXPECT_DOUBLE_EQ(o.maxDepth, 3.5);
  EXPECT_DOUBLE_EQ(o.fx, 517.3);  // untouched default

  mrpt::config::CConfigFileMemory saved;
  o.saveToConfigFile(saved, "S");
  CRgbdSimulator::TOptions back;
  back.loadFromConfigFile(saved, "S");
  EXPECT_EQ(back.scene, o.scene);
  EXPECT_TRUE(back.furniture);
  EXPECT_EQ(back.frames, o.frames);
  EXPECT_DOUBLE_EQ(back.baseTimestamp, o.baseTimestamp);
  EXPECT_DOUBLE_EQ(back.cx, o.cx);
  EXPECT_DOUBLE_EQ(back.commonShiftPx, 0.4);
  EXPECT_DOUBLE_EQ(back.exposureMs, 12.5);
  EXPECT_EQ(back.exposureSamples, 5u);
  EXPECT_DOUBLE_EQ(back.depthRadialBias, -0.025);
  EXPECT_DOUBLE_EQ(back.stampDelay, 0.009);
  // The camera it simulates describes the shift.
  EXPECT_DOUBLE_EQ(CRgbdSimulator(o).sensorDescription().common_pixel_sigma_px, 0.4);

  auto expectError = [](const std::string& key, const std::string& value)
  {
    mrpt::config::CConfigFileMemory bad;
    bad.write("RgbdSimulator", key, value);
    CRgbdSimulator::TOptions x;
    try
    {
      x.loadFromConfigFile(bad, "RgbdSimulator");
      ADD_FAILURE() << key << " = " << value << " accepted";
    }
    catch (const std::invalid_argument& e)
    {
      EXPECT_NE(std::string(e.what()).find("[RgbdSimulator] " + key), std::string::npos)
          << e.what();
    }
  };
  expectError("frames", "abc");
  expectError("frames", "1");
  expectError("frames", "-5");
  expectError("scene", "kitchen");
  expectError("furniture", "maybe");
  expectError("max_depth", "20");
  expectError("fps", "0");
  expectError("noise", "maybe");
  expectError("depth_time_offset", "0.05");
  expectError("depth_radial_bias", "0.5");
  expectError("stamp_delay", "-0.001");
  expectError("stamp_delay", "0.02");
  expectError("depth_radial_bias", "x");
  expectError("rolling_shutter_ms", "-1");
  expectError("rolling_shutter_ms", "40");  // longer than a 30 Hz frame
  expectError("framez", "10");              // unknown key
  expectError("noise_model", "gauss");
  expectError("disparity_bf", "0");
  expectError("lateral_sigma_px", "-1");
  expectError("common_shift_px", "-0.5");
  expectError("common_shift_px", "11");
  expectError("exposure_ms", "-1");
  expectError("exposure_ms", "40");  // longer than a 30 Hz frame
  expectError("exposure_samples", "4");
  expectError("exposure_samples", "1");
  expectError("exposure_samples", "65");
  expectError("depth_registered", "perhaps");
  expectError("depth_fx", "-500");
  expectError("depth_cx", "900");
  expectError("depth_pose_in_colour", "[1 2 3]");
  expectError("layout", "kitti");
  expectError("colour_dist", "[0.1 x]");
  expectError("colour_dist", "[0 0 0 0 0 0]");  // six values
  expectError("colour_dist", "[-2]");           // folds back within the image
  {
    mrpt::config::CConfigFileMemory bad;
    bad.write("RgbdSimulator", "colour_dist", "[0.1]");
    bad.write("RgbdSimulator", "common_shift_px", "0.5");
    CRgbdSimulator::TOptions x;
    EXPECT_THROW(x.loadFromConfigFile(bad, "RgbdSimulator"), std::invalid_argument);
  }
  {
    mrpt::config::CConfigFileMemory bad;
    bad.write("RgbdSimulator", "layout", "7scenes");
    bad.write("RgbdSimulator", "camera_y_up", "true");
    CRgbdSimulator::TOptions x;
    EXPECT_THROW(x.loadFromConfigFile(bad, "RgbdSimulator"), std::invalid_argument);
  }
}

// The accelerometer reads gravity plus the path's acceleration, in the
// Kinect's axes: turned into the world by the ground truth, its mean over the
// closed loop (whose accelerations average out) is 9.81 m/s^2 straight up.
TEST(RgbdSimulator, AccelerometerReadsGravityInTheKinectAxes)
{
  const CRgbdSimulator sim(opts("textured", false, 90));
  mrpt::math::TVector3D mean(0, 0, 0);
  for (std::size_t i = 0; i < 90; ++i)
  {
    const auto kinect = sim.accelerometerReading(i);
    // Kinect axes = optical axes turned half a turn about the optical axis.
    const mrpt::math::TVector3D optical(-kinect.x, -kinect.y, kinect.z);
    mean = mean + sim.groundTruthPose(i).rotateVector(optical) * (1.0 / 90);
  }
  EXPECT_NEAR(mean.x, 0, 0.02);
  EXPECT_NEAR(mean.y, 0, 0.02);
  EXPECT_NEAR(mean.z, 9.81, 0.02);
  // Not gravity alone: the hand-held path accelerates.
  double most = 0;
  for (std::size_t i = 0; i < 90; ++i)
    most = std::max(most, std::abs(sim.accelerometerReading(i).norm() - 9.81));
  EXPECT_GT(most, 0.1);
}

TEST(RgbdSimulator, WritesTumLayoutMatchingRenderedFrames)
{
  const std::string dir = roislam::testing::makeTempDir("sim_write");
  const fs::path out = fs::path(dir) / "seq";
  auto o = opts("textured", true, 4);
  o.seed = 9;
  {
    CRgbdSimulator sim(o);
    const auto st = sim.writeSequence(out.string());
    EXPECT_EQ(st.frames, 4u);
  }
  for (const char* f :
       {"rgb.txt", "depth.txt", "groundtruth.txt", "accelerometer.txt", "camera.ini",
        "simulator.ini"})
    EXPECT_TRUE(fs::is_regular_file(out / f)) << f;
  EXPECT_EQ(countLines(out / "rgb.txt"), 4u);
  EXPECT_EQ(roislam::io::loadTumAccelerometer((out / "accelerometer.txt").string()).size(), 4u);
  EXPECT_EQ(countLines(out / "depth.txt"), 4u);
  // Nothing but the output is left in the parent folder.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);

  {  // one rendering simulator per thread at a time
    CRgbdSimulator sim(o);
    const auto gt = roislam::io::loadTumTrajectory((out / "groundtruth.txt").string());
    ASSERT_EQ(gt.size(), 4u);
    for (std::size_t i = 0; i < 4; ++i)
    {
      EXPECT_NEAR(gt[i].timestamp, sim.timestamp(i), 1e-6);
      EXPECT_LT((gt[i].pose.translation() - sim.groundTruthPose(i).translation()).norm(), 1e-9);
    }
    EXPECT_NEAR(sim.timestamp(1) - sim.timestamp(0), 1 / 30.0, 1e-6);

    // Depth PNG = rendered depth x 5000, rounded; same seed gives the same noise.
    const auto f2 = sim.renderFrame(2);
    char name[64];
    std::snprintf(name, sizeof(name), "depth/%.6f.png", f2.depthTimestamp);
    const cv::Mat png = cv::imread((out / name).string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(png.type(), CV_16UC1) << name;
    cv::Mat expected;
    f2.depth.convertTo(expected, CV_16UC1, 5000.0);
    EXPECT_EQ(cv::norm(png, expected, cv::NORM_INF), 0.0);
    std::snprintf(name, sizeof(name), "rgb/%.6f.png", f2.timestamp);
    const cv::Mat rgb = cv::imread((out / name).string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(rgb.type(), CV_8UC3);
    EXPECT_EQ(cv::norm(rgb, f2.rgb, cv::NORM_INF), 0.0);

    mrpt::img::TCamera cam;
    cam.loadFromConfigFile(
        "CAMERA_PARAMS", mrpt::config::CConfigFile((out / "camera.ini").string()));
    EXPECT_DOUBLE_EQ(cam.fx(), 517.3);
    EXPECT_DOUBLE_EQ(cam.cy(), 255.3);
    EXPECT_EQ(cam.ncols, 640u);
    // camera.ini is the whole sensor description.
    roislam::io::TSensorDescription d;
    d.loadFromConfigFile(
        mrpt::config::CConfigFile((out / "camera.ini").string()), "SensorDescription");
    EXPECT_EQ(d.name, "rgbd-simul");
    EXPECT_TRUE(d.depth_registered);
    EXPECT_DOUBLE_EQ(d.rolling_shutter_ms, o.rollingShutterMs);
    EXPECT_DOUBLE_EQ(d.frame_rate, 30);
    EXPECT_DOUBLE_EQ(d.depth_scale, 5000);
    EXPECT_EQ(d.depth_noise.model, "kinect");
  }
  // Writing again is refused unless overwrite, which replaces the earlier output.
  auto o2 = o;
  o2.frames = 2;
  EXPECT_THROW(CRgbdSimulator(o2).writeSequence(out.string()), std::runtime_error);
  EXPECT_EQ(countLines(out / "rgb.txt"), 4u);
  CRgbdSimulator(o2).writeSequence(out.string(), true);
  EXPECT_EQ(countLines(out / "rgb.txt"), 2u);
  fs::remove_all(dir);
}

// stamp_delay writes each frame's stamps later than its images were taken,
// as a driver stamps a frame when it arrives; camera.ini says so, and the
// folder reader gives the frames back at the times they were taken.
TEST(RgbdSimulator, DelayedStampsAreReadBackAtTheTimeTheImagesWereTaken)
{
  const std::string dir = roislam::testing::makeTempDir("sim_delay");
  const fs::path out = fs::path(dir) / "seq";
  auto o = opts("textured", false, 3);
  o.stampDelay = 0.009;
  o.depthTimeOffset = 0.004;
  CRgbdSimulator sim(o);
  sim.writeSequence(out.string());
  const auto gt = roislam::io::loadTumTrajectory((out / "groundtruth.txt").string());
  ASSERT_EQ(gt.size(), 3u);
  auto source = roislam::io::CFrameSource::open(out.string());
  EXPECT_DOUBLE_EQ(source->sensor().sensor.colour_time_offset_ms, -9);
  const auto* tum = dynamic_cast<const roislam::io::CTumFrameSource*>(source.get());
  ASSERT_NE(tum, nullptr);
  for (std::size_t i = 0; i < 3; ++i)
  {
    // Written late; the truth at the true times.
    EXPECT_NEAR(tum->entries()[i].rgbStamp, sim.timestamp(i) + 0.009, 1e-6) << i;
    EXPECT_NEAR(tum->entries()[i].depthStamp, sim.timestamp(i) + 0.013, 1e-6) << i;
    EXPECT_NEAR(gt[i].timestamp, sim.timestamp(i), 1e-6) << i;
    // Read back when taken: colour at the truth's time, depth at its stamp.
    const auto f = source->next();
    ASSERT_TRUE(f);
    EXPECT_NEAR(f->timestamp, gt[i].timestamp, 1e-6) << i;
    EXPECT_NEAR(f->depthTimestamp, sim.timestamp(i) + 0.013, 1e-6) << i;
  }
  // 7-Scenes' layout has no stamps to delay.
  auto seven = opts("textured", false, 3);
  seven.layout = "7scenes";
  seven.stampDelay = 0.009;
  EXPECT_THROW(CRgbdSimulator{seven}, std::invalid_argument);
  fs::remove_all(dir);
}

// layout = 7scenes writes Microsoft 7-Scenes' own files, which the TUM
// reader reads back as the same frames (depth to the millimetre) and the
// same ground truth as the TUM layout; the shipped config renders the
// "7scenes" preset's cameras.
TEST(RgbdSimulator, WritesSevenScenesLayoutReadBackAsTheTumOne)
{
  roislam::testing::CTempDir dir("sim_write_7scenes");
  auto o = opts("textured", true, 3);
  o.depthRegistered = false;
  o.depthFx = o.depthFy = 585;
  o.depthPoseInColour = "[-0.025 0.002 0.001 2 -1 0.5]";
  const fs::path tum = fs::path(dir.path()) / "tum", seven = fs::path(dir.path()) / "seq-01";
  CRgbdSimulator(o).writeSequence(tum.string());
  o.layout = "7scenes";
  CRgbdSimulator(o).writeSequence(seven.string());
  for (const char* f :
       {"frame-000000.color.png", "frame-000002.depth.png", "frame-000001.pose.txt",
        "simulator.ini"})
    EXPECT_TRUE(fs::is_regular_file(seven / f)) << f;
  for (const char* f : {"rgb.txt", "camera.ini", "groundtruth.txt", "rgb"})
    EXPECT_FALSE(fs::exists(seven / f)) << f;

  auto choice = roislam::io::resolveSensor("auto", tum.string());
  const auto a = roislam::io::CFrameSource::open(tum.string());
  choice.sensor.depth_scale = 1000;
  roislam::io::CTumFrameSource b(seven.string(), choice, roislam::io::CTumFrameSource::TOptions());
  ASSERT_EQ(b.size(), 3u);
  const auto gtA = roislam::io::loadTumTrajectory(*a->groundTruthFile());
  const auto gtB = roislam::io::loadTumTrajectory(*b.groundTruthFile());
  ASSERT_EQ(gtB.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i)
  {
    const auto fa = a->next(), fb = b.next();
    ASSERT_TRUE(fa && fb);
    EXPECT_EQ(cv::norm(fa->rgb, fb->rgb, cv::NORM_INF), 0.0);
    // Both registered into the colour camera from depth rounded to 0.2 mm
    // (TUM) and to 1 mm (7-Scenes): the same readings within 0.8 mm, on the
    // same pixels.
    cv::Mat diff = cv::abs(fa->depth - fb->depth), valid = fa->depth > 0;
    EXPECT_LT(cv::countNonZero(valid != (fb->depth > 0)), cv::countNonZero(valid) / 500) << i;
    // Where two surfaces meet, the rounding can decide which one a colour
    // pixel sees, or whether it sees any (measured: 240-245 of 237,600
    // pixels a frame differ, 1-3 have a reading in one only).
    const int off = cv::countNonZero((diff > 0.0008) & valid);
    EXPECT_LT(off, cv::countNonZero(valid) / 500) << i;
    EXPECT_NEAR(gtB[i].timestamp, i / 30.0, 1e-12);
    EXPECT_LT((gtA[i].pose - gtB[i].pose).translation().norm(), 1e-9) << i;
  }

  // The shipped config renders the preset's cameras.
  CRgbdSimulator::TOptions shipped;
  shipped.loadFromConfigFile(
      mrpt::config::CConfigFile(roislam::testing::sourceDir() + "/config/rgbd-simul-7scenes.ini"),
      "RgbdSimulator");
  EXPECT_EQ(shipped.layout, "7scenes");
  const auto rendered = CRgbdSimulator(shipped).sensorDescription();
  const auto preset = roislam::io::sensorPreset("7scenes");
  EXPECT_EQ(rendered.colour.intrinsicParams, preset.colour.intrinsicParams);
  EXPECT_EQ(rendered.depth.intrinsicParams, preset.depth.intrinsicParams);
  EXPECT_EQ(rendered.depth_registered, preset.depth_registered);
  EXPECT_EQ(rendered.depth_pose_in_colour.asString(), preset.depth_pose_in_colour.asString());
  EXPECT_DOUBLE_EQ(rendered.rolling_shutter_ms, preset.rolling_shutter_ms);
  EXPECT_DOUBLE_EQ(rendered.frame_rate, preset.frame_rate);
}

TEST(RgbdSimulator, BadOutputPathsFailCleanly)
{
  const std::string dir = roislam::testing::makeTempDir("sim_bad");
  const fs::path file = fs::path(dir) / "plain.txt";
  std::ofstream(file) << "x";
  CRgbdSimulator sim(opts("featureless", false, 2));
  // Parent is a regular file.
  try
  {
    sim.writeSequence((file / "seq").string());
    ADD_FAILURE() << "no error for an output below a file";
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
  }
  // A non-empty folder that is not ours is never replaced.
  const fs::path foreign = fs::path(dir) / "foreign";
  fs::create_directories(foreign);
  std::ofstream(foreign / "keep.txt") << "precious";
  EXPECT_THROW(sim.writeSequence(foreign.string()), std::runtime_error);
  EXPECT_THROW(sim.writeSequence(foreign.string(), true), std::runtime_error);
  EXPECT_TRUE(fs::exists(foreign / "keep.txt"));
  EXPECT_FALSE(fs::exists(foreign / "rgb.txt"));
  // No temporary folders left behind.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 2);
  fs::remove_all(dir);
}

TEST(RgbdSimulator, OneRenderingSimulatorPerThread)
{
  cv::Mat first;
  {
    CRgbdSimulator a(opts("textured", false, 4));
    first = a.renderFrame(1).rgb;
    CRgbdSimulator b(opts("featureless", false, 4));
    // b would share a's per-thread GL state and render garbage: refused.
    EXPECT_THROW(b.renderFrame(1), std::logic_error);
    EXPECT_EQ(cv::norm(first, a.renderFrame(1).rgb, cv::NORM_INF), 0.0);
  }
  // Once a is gone, a new simulator renders normally.
  CRgbdSimulator c(opts("textured", false, 4));
  EXPECT_EQ(cv::norm(first, c.renderFrame(1).rgb, cv::NORM_INF), 0.0);
}
