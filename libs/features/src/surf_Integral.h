/* Private to CSurf: box sums and Haar wavelets on an integral image, shared by
 * the Fast-Hessian detector and the orientation/descriptor stage.
 */
#pragma once

#include <algorithm>
#include <cstdint>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace roislam::features::surf
{
/** Integral image of an 8-bit grey image: (rows+1) x (cols+1) int32, so box
 *  sums of 0..255 pixels over a whole 640x480 frame cannot overflow. */
class TIntegral
{
 public:
  explicit TIntegral(const cv::Mat& grey8u)
  {
    cv::integral(grey8u, m_sum, CV_32S);
    rows = grey8u.rows;
    cols = grey8u.cols;
    stride = static_cast<int>(m_sum.step1());
    data = m_sum.ptr<int32_t>(0);
  }

  /** Sum over pixels [x0, x1) x [y0, y1), clipped to the image: samples near
   *  the border then see a truncated window instead of reading outside. */
  int boxClamped(int x0, int y0, int x1, int y1) const
  {
    x0 = std::clamp(x0, 0, cols);
    x1 = std::clamp(x1, 0, cols);
    y0 = std::clamp(y0, 0, rows);
    y1 = std::clamp(y1, 0, rows);
    if (x1 <= x0 || y1 <= y0)
      return 0;
    return data[y1 * stride + x1] - data[y0 * stride + x1] - data[y1 * stride + x0] +
           data[y0 * stride + x0];
  }

  /** Haar wavelet responses (right minus left, bottom minus top) of side 2*half
   *  whose centre is the corner between pixels (x-1, y-1) and (x, y). */
  void haar(int x, int y, int half, float& dx, float& dy) const
  {
    if (x - half >= 0 && y - half >= 0 && x + half <= cols && y + half <= rows)
    {
      // Fast path: 9 lookups on a 3x3 lattice of corners, no clamping.
      const int32_t* p = data + (y - half) * stride + (x - half);
      const int s2 = half * stride;
      const int a = p[0], b = p[half], c = p[2 * half];
      const int d = p[s2], f = p[s2 + 2 * half];
      const int g = p[2 * s2], h = p[2 * s2 + half], i = p[2 * s2 + 2 * half];
      // left = [x-half,x) x [y-half,y+half): a,b,g,h ; right: b,c,h,i
      const int left = h - b - g + a;
      const int right = i - c - h + b;
      const int top = f - c - d + a;
      const int bottom = i - f - g + d;
      dx = static_cast<float>(right - left);
      dy = static_cast<float>(bottom - top);
      return;
    }
    dx = static_cast<float>(
        boxClamped(x, y - half, x + half, y + half) - boxClamped(x - half, y - half, x, y + half));
    dy = static_cast<float>(
        boxClamped(x - half, y, x + half, y + half) - boxClamped(x - half, y - half, x + half, y));
  }

  int rows = 0, cols = 0, stride = 0;
  const int32_t* data = nullptr;

 private:
  cv::Mat m_sum;
};
}  // namespace roislam::features::surf
