#include "roislam/roi/HueEdges.h"

#include <array>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace roislam::roi
{
namespace
{
/** Integer scale of the hue unit vector: Sobel of a step between opposite
 *  hues reaches 8 K = 8192, combined over both components 11585, within int16. */
constexpr double kScale = 1024;

cv::Mat hsvOf(const cv::Mat& bgr)
{
  if (bgr.type() != CV_8UC3)
    throw std::invalid_argument("hue edges need an 8-bit BGR image");
  cv::Mat hsv;
  cv::cvtColor(bgr, hsv, cv::COLOR_BGR2HSV);
  return hsv;
}

cv::Mat reliableOf(const cv::Mat& hsv, const THueEdgeParams& p)
{
  cv::Mat reliable;
  const double s = std::ceil(p.minSaturation * 255), v = std::ceil(p.minValue * 255);
  cv::inRange(hsv, cv::Scalar(0, s, v), cv::Scalar(255, 255, 255), reliable);
  return reliable;
}

/** Canny threshold of a hue step of `deg` degrees (see the header). */
double stepThreshold(double deg)
{
  return 8 * kScale * std::sin(0.5 * deg * M_PI / 180);
}
}  // namespace

cv::Mat reliableHueMask(const cv::Mat& bgr, const THueEdgeParams& params)
{
  return reliableOf(hsvOf(bgr), params);
}

cv::Mat hueEdges(const cv::Mat& bgr, const THueEdgeParams& params)
{
  const cv::Mat hsv = hsvOf(bgr);
  // OpenCV's 8-bit hue: 0..179, 2 degrees per unit.
  std::array<short, 256> cosLut{}, sinLut{};
  for (int h = 0; h < 180; ++h)
  {
    cosLut[h] = static_cast<short>(std::lround(kScale * std::cos(h * M_PI / 90)));
    sinLut[h] = static_cast<short>(std::lround(kScale * std::sin(h * M_PI / 90)));
  }
  cv::Mat c(hsv.size(), CV_16SC1), s(hsv.size(), CV_16SC1);
  for (int r = 0; r < hsv.rows; ++r)
  {
    const cv::Vec3b* px = hsv.ptr<cv::Vec3b>(r);
    short* cr = c.ptr<short>(r);
    short* sr = s.ptr<short>(r);
    for (int x = 0; x < hsv.cols; ++x)
    {
      cr[x] = cosLut[px[x][0]];
      sr[x] = sinLut[px[x][0]];
    }
  }
  cv::Mat cx, cy, sx, sy;
  cv::Sobel(c, cx, CV_32F, 1, 0, 3);
  cv::Sobel(c, cy, CV_32F, 0, 1, 3);
  cv::Sobel(s, sx, CV_32F, 1, 0, 3);
  cv::Sobel(s, sy, CV_32F, 0, 1, 3);
  // Valid where the whole 3x3 window has a reliable hue.
  cv::Mat valid;
  cv::erode(reliableOf(hsv, params), valid, cv::Mat(), cv::Point(-1, -1), 1, cv::BORDER_REPLICATE);

  // One derivative pair for Canny: per axis the norm over both components,
  // and dy's sign from the two axes' dot product (the orientation Canny's
  // non-maximum suppression needs for diagonal edges).
  cv::Mat dx(hsv.size(), CV_16SC1), dy(hsv.size(), CV_16SC1);
  for (int r = 0; r < hsv.rows; ++r)
  {
    const float *a = cx.ptr<float>(r), *b = sx.ptr<float>(r), *e = cy.ptr<float>(r),
                *f = sy.ptr<float>(r);
    const uchar* ok = valid.ptr<uchar>(r);
    short* outX = dx.ptr<short>(r);
    short* outY = dy.ptr<short>(r);
    for (int x = 0; x < hsv.cols; ++x)
    {
      if (!ok[x])
      {
        outX[x] = outY[x] = 0;
        continue;
      }
      const float gx = std::sqrt(a[x] * a[x] + b[x] * b[x]);
      const float gy = std::sqrt(e[x] * e[x] + f[x] * f[x]);
      const bool negative = a[x] * e[x] + b[x] * f[x] < 0;
      outX[x] = static_cast<short>(std::lround(gx));
      outY[x] = static_cast<short>(std::lround(negative ? -gy : gy));
    }
  }
  cv::Mat edges;
  cv::Canny(dx, dy, edges, stepThreshold(params.lowDeg), stepThreshold(params.highDeg), true);
  return edges;
}
}  // namespace roislam::roi
