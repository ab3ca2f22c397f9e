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

  /** Integral at a fractional corner (x, y): bilinear interpolation of the
   *  four neighbouring corners is exact for a piecewise-constant image, so box
   *  sums with fractional corners are true area sums. Clamped to the image. */
  float at(float x, float y) const
  {
    x = std::clamp(x, 0.0f, static_cast<float>(cols) - 1e-3f);
    y = std::clamp(y, 0.0f, static_cast<float>(rows) - 1e-3f);
    const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
    const float fx = x - x0, fy = y - y0;
    const int32_t* p = data + y0 * stride + x0;
    const float top = p[0] + fx * static_cast<float>(p[1] - p[0]);
    const float bot = p[stride] + fx * static_cast<float>(p[stride + 1] - p[stride]);
    return top + fy * (bot - top);
  }

  /** Haar wavelets of side 2*half centred exactly at the continuous pixel
   *  position (x, y) (pixel centres at integers), with fractional corners. */
  void haarAt(float x, float y, float half, float& dx, float& dy) const
  {
    // Corner coordinates: pixel (x, y) spans [x, x+1), its centre is x + 0.5.
    const float cx = x + 0.5f, cy = y + 0.5f;
    const float xs[3] = {cx - half, cx, cx + half}, ys[3] = {cy - half, cy, cy + half};
    float v[3][3];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        v[r][c] = at(xs[c], ys[r]);
    const float left = v[2][1] - v[0][1] - v[2][0] + v[0][0];
    const float right = v[2][2] - v[0][2] - v[2][1] + v[0][1];
    const float top = v[1][2] - v[0][2] - v[1][0] + v[0][0];
    const float bottom = v[2][2] - v[1][2] - v[2][0] + v[1][0];
    dx = right - left;
    dy = bottom - top;
  }

  int rows = 0, cols = 0, stride = 0;
  const int32_t* data = nullptr;

 private:
  cv::Mat m_sum;
};
}  // namespace roislam::features::surf
