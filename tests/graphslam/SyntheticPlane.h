/* Test helper: RGB-D frames of a camera moving in front of a textured wall
 * (plane z = depth in the world, optical frame convention), with exact
 * geometry, so the deciders can be fed observations with known poses. */
#pragma once

#include <mrpt/img/TCamera.h>
#include <mrpt/poses/CPose3D.h>
#include <roislam/io/CameraPresets.h>
#include <roislam/io/TRGBDFrame.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

namespace roislam::testing
{
class CSyntheticPlane
{
 public:
  /** Texture covers world x in [-2, 2], y in [-1.5, 1.5] at 2 mm per texel. */
  explicit CSyntheticPlane(double depth = 2.0) : m_depth(depth)
  {
    cv::RNG rng(12345);
    cv::Mat noise(1500, 2000, CV_8UC1);
    rng.fill(noise, cv::RNG::UNIFORM, 0, 255);
    cv::Mat blobs;
    cv::resize(noise(cv::Rect(0, 0, 200, 150)), blobs, noise.size(), 0, 0, cv::INTER_NEAREST);
    cv::GaussianBlur(noise, noise, cv::Size(3, 3), 0);
    cv::addWeighted(noise, 0.5, blobs, 0.5, 0, m_texture);
    m_camera = io::cameraPreset("ros");  // 640 x 480, f 525 px, no distortion
  }

  /** The frame seen from `pose` (optical camera in the world). */
  io::TRGBDFrame render(const mrpt::poses::CPose3D& pose, std::size_t index, double stamp) const
  {
    io::TRGBDFrame f;
    f.index = index;
    f.timestamp = f.depthTimestamp = stamp;
    f.camera = m_camera;
    cv::Mat mapx(480, 640, CV_32F), mapy(480, 640, CV_32F);
    f.depth = cv::Mat(480, 640, CV_32F, cv::Scalar(0));
    const auto R = pose.getRotationMatrix();
    const auto t = pose.translation();
    for (int v = 0; v < 480; ++v)
      for (int u = 0; u < 640; ++u)
      {
        // Ray in the world; intersect with the plane z = m_depth.
        const double rx = (u - m_camera.cx()) / m_camera.fx(),
                     ry = (v - m_camera.cy()) / m_camera.fy();
        const double dx = R(0, 0) * rx + R(0, 1) * ry + R(0, 2);
        const double dy = R(1, 0) * rx + R(1, 1) * ry + R(1, 2);
        const double dz = R(2, 0) * rx + R(2, 1) * ry + R(2, 2);
        const double s = (m_depth - t.z) / dz;
        const double wx = t.x + s * dx, wy = t.y + s * dy;
        mapx.at<float>(v, u) = static_cast<float>((wx + 2.0) / 0.002);
        mapy.at<float>(v, u) = static_cast<float>((wy + 1.5) / 0.002);
        f.depth.at<float>(v, u) = static_cast<float>(s);  // z in the camera = s (unit z ray)
      }
    cv::Mat grey;
    cv::remap(m_texture, grey, mapx, mapy, cv::INTER_LINEAR);
    cv::cvtColor(grey, f.rgb, cv::COLOR_GRAY2BGR);
    return f;
  }

  const mrpt::img::TCamera& camera() const { return m_camera; }

 private:
  double m_depth;
  cv::Mat m_texture;
  mrpt::img::TCamera m_camera;
};

/** Camera path: out along +x to 0.6 m over 20 frames, then back to 0. */
inline mrpt::poses::CPose3D outAndBackPose(int i)
{
  const double x = i <= 20 ? 0.03 * i : 0.03 * (40 - i);
  return mrpt::poses::CPose3D(x, 0.01 * std::sin(0.3 * i), 0, 0, 0, 0);
}
}  // namespace roislam::testing
