/* Test helper: ray-cast RGB-D frames of a closed box room (walls, floor,
 * ceiling) seen by a pinhole camera at known poses (optical frame, x right,
 * y down, z forward). Textures are random grey blocks with a chosen contrast:
 * high contrast gives Canny edges (a ROI) and features, low contrast gives
 * features but no Canny edges (no ROI), zero contrast is featureless. */
#pragma once

#include <mrpt/poses/CPose3D.h>
#include <roislam/io/CameraPresets.h>
#include <roislam/io/TRGBDFrame.h>

#include <cmath>
#include <cstdint>
#include <limits>

namespace roislam::frontend::testing
{
/** 640 x 480, f 525 px, no distortion. */
inline mrpt::img::TCamera syntheticCamera()
{
  return io::cameraPreset("ros");
}

/** contrast: grey amplitude of the blocks around 128 (0 = uniform grey). */
inline io::TRGBDFrame renderRoom(
    const mrpt::poses::CPose3D& pose, double contrast, std::size_t index, double stamp)
{
  const auto cam = syntheticCamera();
  io::TRGBDFrame f;
  f.index = index;
  f.timestamp = stamp;
  f.depthTimestamp = stamp;
  f.camera = cam;
  f.rgb.create(480, 640, CV_8UC3);
  f.depth.create(480, 640, CV_32FC1);
  // Planes as (axis, value): x = -1.5 / 1.8, y = -1.2 / 1.2, z = -1 / 3.
  const int axes[6] = {0, 0, 1, 1, 2, 2};
  const double vals[6] = {-1.5, 1.8, -1.2, 1.2, -1.0, 3.0};
  const auto R = pose.getRotationMatrix();
  const double o[3] = {pose.x(), pose.y(), pose.z()};
  for (int v = 0; v < 480; ++v)
    for (int u = 0; u < 640; ++u)
    {
      const double dc[3] = {(u - cam.cx()) / cam.fx(), (v - cam.cy()) / cam.fy(), 1.0};
      double dw[3];
      for (int r = 0; r < 3; ++r)
        dw[r] = R(r, 0) * dc[0] + R(r, 1) * dc[1] + R(r, 2) * dc[2];
      double best = std::numeric_limits<double>::max();
      int bp = -1;
      for (int p = 0; p < 6; ++p)
      {
        const int a = axes[p];
        if (std::abs(dw[a]) < 1e-12)
          continue;
        const double s = (vals[p] - o[a]) / dw[a];
        if (s > 0 && s < best)
        {
          best = s;
          bp = p;
        }
      }
      // s scales a ray whose camera z is 1, so s is the depth.
      double g = 128;
      if (bp >= 0)
      {
        const int a = axes[bp];
        const double q[3] = {o[0] + best * dw[0], o[1] + best * dw[1], o[2] + best * dw[2]};
        const int i = static_cast<int>(std::floor(q[(a + 1) % 3] / 0.06));
        const int j = static_cast<int>(std::floor(q[(a + 2) % 3] / 0.06));
        std::uint32_t h = static_cast<std::uint32_t>(i) * 73856093u ^
                          static_cast<std::uint32_t>(j) * 19349663u ^
                          static_cast<std::uint32_t>(bp) * 83492791u;
        h ^= h >> 13;
        h *= 0x5bd1e995u;
        h ^= h >> 15;
        g = 128 + contrast * ((static_cast<double>(h % 1000) / 999.0) * 2 - 1);
      }
      const auto c = static_cast<unsigned char>(std::lround(std::clamp(g, 0.0, 255.0)));
      f.rgb.at<cv::Vec3b>(v, u) = cv::Vec3b(c, c, c);
      f.depth.at<float>(v, u) = bp >= 0 ? static_cast<float>(best) : 0.f;
    }
  return f;
}

/** Ground-truth pose of frame k of the test trajectory: slow translation and
 *  rotation about all axes, starting at the room's origin. */
inline mrpt::poses::CPose3D trajectoryPose(std::size_t k)
{
  const double t = static_cast<double>(k);
  return mrpt::poses::CPose3D(0.012 * t, -0.004 * t, 0.01 * t, 0.006 * t, -0.004 * t, 0.003 * t);
}
}  // namespace roislam::frontend::testing
