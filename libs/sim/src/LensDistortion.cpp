#include "LensDistortion.h"

#include <roislam/common/IniRead.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace roislam::sim::detail
{
std::optional<TDistortion> parseDistortion(const std::string& text)
{
  std::string t = text;
  for (char& c : t)
    if (c == '[' || c == ']' || c == ',' || c == '\t')
      c = ' ';
  std::istringstream in(t);
  TDistortion d{};
  std::size_t n = 0;
  for (std::string word; in >> word;)
  {
    const auto v = common::parseDouble(word);
    if (!v || n == d.size())
      return std::nullopt;
    d[n++] = *v;
  }
  if (n == 0)
    return std::nullopt;
  return d;
}

bool isZero(const TDistortion& d)
{
  return std::all_of(d.begin(), d.end(), [](double v) { return v == 0; });
}

cv::Point2d distortNormalised(const TDistortion& d, cv::Point2d p)
{
  const double r2 = p.x * p.x + p.y * p.y;
  const double radial = 1 + r2 * (d[0] + r2 * (d[1] + r2 * d[4]));
  return {
      p.x * radial + 2 * d[2] * p.x * p.y + d[3] * (r2 + 2 * p.x * p.x),
      p.y * radial + d[2] * (r2 + 2 * p.y * p.y) + 2 * d[3] * p.x * p.y};
}

namespace
{
/** The undistorted point that distorts to q: Newton's method from q (the
 *  Jacobian by central differences). Nothing when it does not converge or
 *  the map folds there (its Jacobian's determinant not positive). */
std::optional<cv::Point2d> undistortNormalised(const TDistortion& d, cv::Point2d q)
{
  cv::Point2d p = q;
  const double h = 1e-6;
  for (int it = 0; it < 30; ++it)
  {
    const cv::Point2d e = distortNormalised(d, p) - q;
    const cv::Point2d dx = (distortNormalised(d, p + cv::Point2d(h, 0)) -
                            distortNormalised(d, p - cv::Point2d(h, 0))) /
                           (2 * h);
    const cv::Point2d dy = (distortNormalised(d, p + cv::Point2d(0, h)) -
                            distortNormalised(d, p - cv::Point2d(0, h))) /
                           (2 * h);
    const double det = dx.x * dy.y - dy.x * dx.y;
    if (!(det > 0.05))
      return std::nullopt;
    if (std::abs(e.x) + std::abs(e.y) < 1e-10)
      return p;
    p -= cv::Point2d(dy.y * e.x - dy.x * e.y, -dx.y * e.x + dx.x * e.y) / det;
  }
  const cv::Point2d e = distortNormalised(d, p) - q;
  if (std::abs(e.x) + std::abs(e.y) < 1e-8)
    return p;
  return std::nullopt;
}
}  // namespace

TDistortionMap makeDistortionMap(
    const TDistortion& d, unsigned W, unsigned H, double fx, double fy, double cx, double cy,
    unsigned ss)
{
  // Every supersampled output pixel's undistorted normalised point (the
  // output pixel centres are among them for odd ss; computed apart below).
  const int Ws = int(W * ss), Hs = int(H * ss);
  cv::Mat undist(Hs, Ws, CV_64FC2);
  const auto undistortPixel = [&](double u, double v)
  {
    const auto p = undistortNormalised(d, {(u - cx) / fx, (v - cy) / fy});
    if (!p)
    {
      char buf[160];
      std::snprintf(
          buf, sizeof(buf),
          "does not map the image one to one (it folds back near pixel (%.0f, %.0f))", u, v);
      throw std::invalid_argument(buf);
    }
    return *p;
  };
  // The pinhole's reach: a supersampled render's samples (a + 0.5) / ss - 0.5
  // for a in [0, W ss - 1], kept clear of its last row and column by the
  // bilinear lookup.
  const double lo = 0.5 / ss - 0.5, hiU = W - 0.5 - 0.5 / ss, hiV = H - 0.5 - 0.5 / ss;
  double zoom = 1;
  for (int b = 0; b < Hs; ++b)
    for (int a = 0; a < Ws; ++a)
    {
      const cv::Point2d p = undistortPixel((a + 0.5) / ss - 0.5, (b + 0.5) / ss - 0.5);
      undist.at<cv::Vec2d>(b, a) = {p.x, p.y};
      const double u = fx * p.x, v = fy * p.y;  // from the principal point
      zoom = std::max(
          {zoom, u > 0 ? u / (hiU - cx) : u / (lo - cx), v > 0 ? v / (hiV - cy) : v / (lo - cy)});
    }
  if (zoom > 2)
    throw std::invalid_argument("needs the pinhole render zoomed out beyond 2x: too strong");
  // A hair more, so that rounding never reaches the render's last sample.
  zoom *= 1 + 1e-6;

  TDistortionMap m;
  m.zoom = zoom;
  m.ssMapX.create(Hs, Ws, CV_32FC1);
  m.ssMapY.create(Hs, Ws, CV_32FC1);
  for (int b = 0; b < Hs; ++b)
    for (int a = 0; a < Ws; ++a)
    {
      const auto p = undist.at<cv::Vec2d>(b, a);
      m.ssMapX.at<float>(b, a) = float(ss * (fx / zoom * p[0] + cx + 0.5) - 0.5);
      m.ssMapY.at<float>(b, a) = float(ss * (fy / zoom * p[1] + cy + 0.5) - 0.5);
    }
  m.centres.create(int(H), int(W), CV_32FC2);
  for (int v = 0; v < int(H); ++v)
    for (int u = 0; u < int(W); ++u)
    {
      const cv::Point2d p = undistortPixel(u, v);
      m.centres.at<cv::Vec2f>(v, u) = {float(fx / zoom * p.x + cx), float(fy / zoom * p.y + cy)};
    }
  return m;
}

cv::Mat depthAtCentres(const mrpt::math::CMatrixFloat& depthSS, unsigned ss, const cv::Mat& centres)
{
  cv::Mat out(centres.size(), CV_32FC1);
  const int maxA = int(depthSS.cols()) - 1, maxB = int(depthSS.rows()) - 1;
  for (int v = 0; v < centres.rows; ++v)
    for (int u = 0; u < centres.cols; ++u)
    {
      const cv::Vec2f c = centres.at<cv::Vec2f>(v, u);
      const double sx = ss * (c[0] + 0.5) - 0.5, sy = ss * (c[1] + 0.5) - 0.5;
      const int a0 = std::clamp(int(std::floor(sx)), 0, maxA - 1);
      const int b0 = std::clamp(int(std::floor(sy)), 0, maxB - 1);
      const float z00 = depthSS(b0, a0), z01 = depthSS(b0, a0 + 1), z10 = depthSS(b0 + 1, a0),
                  z11 = depthSS(b0 + 1, a0 + 1);
      float& o = out.at<float>(v, u);
      if (z00 > 0 && z01 > 0 && z10 > 0 && z11 > 0)
      {
        const double w00 = 1.0 / z00, w01 = 1.0 / z01, w10 = 1.0 / z10, w11 = 1.0 / z11;
        // On a plane inverse depth is affine in the image: bilinear is exact.
        if (std::abs(w00 + w11 - w01 - w10) <= 1e-4 * (w00 + w11))
        {
          const double tx = std::clamp(sx - a0, 0.0, 1.0), ty = std::clamp(sy - b0, 0.0, 1.0);
          const double w =
              (1 - ty) * ((1 - tx) * w00 + tx * w01) + ty * ((1 - tx) * w10 + tx * w11);
          o = float(1.0 / w);
          continue;
        }
      }
      const int a = std::clamp(int(std::lround(sx)), 0, maxA);
      const int b = std::clamp(int(std::lround(sy)), 0, maxB);
      o = depthSS(b, a);
    }
  return out;
}
}  // namespace roislam::sim::detail
