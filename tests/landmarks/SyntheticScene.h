/* Synthetic images for the landmark tests: random textured patches (strong
 * edges, many corners) on a flat grey background, shifted/warped copies, and
 * RGB-D frames with a constant-depth plane. */
#pragma once

#include <mrpt/img/TCamera.h>
#include <roislam/io/CameraPresets.h>
#include <roislam/io/TRGBDFrame.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <random>

namespace roislam::landmarks::test
{
/** A patch of random rectangles, circles and lines (BGR). */
inline cv::Mat texturePatch(unsigned seed, cv::Size size = {220, 180})
{
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> x(0, size.width - 1), y(0, size.height - 1), r(4, 22),
      grey(0, 255), shape(0, 2);
  cv::Mat p(size, CV_8UC3, cv::Scalar(0, 0, 0));
  cv::rectangle(p, cv::Rect({0, 0}, size), cv::Scalar(255, 255, 255), 3);
  for (int i = 0; i < 140; ++i)
  {
    const cv::Scalar c(grey(rng), grey(rng), grey(rng));
    const cv::Point a(x(rng), y(rng));
    switch (shape(rng))
    {
      case 0:
        cv::rectangle(p, a, a + cv::Point(r(rng), r(rng)), c, cv::FILLED);
        break;
      case 1:
        cv::circle(p, a, r(rng) / 2, c, cv::FILLED);
        break;
      default:
        cv::line(p, a, cv::Point(x(rng), y(rng)), c, 2);
    }
  }
  return p;
}

/** The patch pasted at topLeft on a flat grey 640x480 canvas. */
inline cv::Mat onCanvas(const cv::Mat& patch, cv::Point topLeft, cv::Size canvas = {640, 480})
{
  cv::Mat img(canvas, CV_8UC3, cv::Scalar(128, 128, 128));
  patch.copyTo(img(cv::Rect(topLeft, patch.size())));
  return img;
}

/** The image rotated by deg about its centre and shifted (grey border). */
inline cv::Mat warped(const cv::Mat& img, double deg, cv::Point2f shift)
{
  cv::Mat A = cv::getRotationMatrix2D(cv::Point2f(img.cols / 2.f, img.rows / 2.f), deg, 1.0);
  A.at<double>(0, 2) += shift.x;
  A.at<double>(1, 2) += shift.y;
  cv::Mat out;
  cv::warpAffine(
      img, out, A, img.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(128, 128, 128));
  return out;
}

/** 640 x 480, f 525 px, no distortion. */
inline mrpt::img::TCamera testCamera()
{
  return io::cameraPreset("ros");
}

/** A frame of image rgb over a fronto-parallel plane at depth metres. */
inline io::TRGBDFrame makeFrame(std::size_t index, const cv::Mat& rgb, float depth = 1.5f)
{
  io::TRGBDFrame f;
  f.index = index;
  f.timestamp = 100.0 + index / 30.0;
  f.depthTimestamp = f.timestamp;
  f.rgb = rgb;
  f.depth = cv::Mat(rgb.size(), CV_32FC1, cv::Scalar(depth));
  f.camera = testCamera();
  return f;
}
}  // namespace roislam::landmarks::test
