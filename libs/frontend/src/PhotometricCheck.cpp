#include "PhotometricCheck.h"

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

namespace roislam::frontend::detail
{
namespace
{
/** Bilinear grey level at (x, y), or -1 outside the image. */
float sampleGrey(const cv::Mat& grey, float x, float y)
{
  if (!(x >= 0 && y >= 0 && x < grey.cols - 1 && y < grey.rows - 1))
    return -1;
  const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
  const float ax = x - x0, ay = y - y0;
  const uint8_t* r0 = grey.ptr<uint8_t>(y0) + x0;
  const uint8_t* r1 = grey.ptr<uint8_t>(y0 + 1) + x0;
  return (1 - ay) * ((1 - ax) * r0[0] + ax * r0[1]) + ay * ((1 - ax) * r1[0] + ax * r1[1]);
}

/** The samples' absolute grey differences under pose T (x_key = T x_cur),
 *  the median difference removed; -1 where a sample is not seen. */
std::vector<float> differences(
    const TPhotoSamples& s, const cv::Mat& grey, const cv::Mat& K, const cv::Mat& dist,
    const TRigid& T)
{
  const TRigid toCurrent = T.inverse();
  std::vector<cv::Point3f> pts;
  std::vector<std::size_t> idx;
  pts.reserve(s.points.size());
  for (std::size_t i = 0; i < s.points.size(); ++i)
  {
    const Eigen::Vector3d p = toCurrent * s.points[i];
    if (!(p.z() > 0.05))
      continue;
    pts.emplace_back(
        static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()));
    idx.push_back(i);
  }
  std::vector<float> out(s.points.size(), -1.0F);
  if (pts.empty())
    return out;
  std::vector<cv::Point2f> px;
  cv::projectPoints(pts, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, dist, px);
  std::vector<float> signedDiff(s.points.size(), 0.0F), seen;
  for (std::size_t j = 0; j < px.size(); ++j)
  {
    const float g = sampleGrey(grey, px[j].x, px[j].y);
    if (g < 0)
      continue;
    const std::size_t i = idx[j];
    signedDiff[i] = g - s.grey[i];
    out[i] = 0;
    seen.push_back(signedDiff[i]);
  }
  if (seen.empty())
    return out;
  auto mid = seen.begin() + static_cast<std::ptrdiff_t>(seen.size() / 2);
  std::nth_element(seen.begin(), mid, seen.end());
  const float offset = *mid;
  for (std::size_t i = 0; i < out.size(); ++i)
    if (out[i] == 0)
      out[i] = std::abs(signedDiff[i] - offset);
  return out;
}
}  // namespace

TPhotoSamples photoSamples(
    const cv::Mat& grey, const cv::Mat& depth, const cv::Mat& K, const cv::Mat& dist,
    const geometry::TDepthRule& rule, int cellPx)
{
  TPhotoSamples s;
  if (grey.empty() || depth.size() != grey.size() || grey.type() != CV_8UC1 ||
      depth.type() != CV_32FC1 || cellPx < 2)
    return s;
  cv::Mat gx, gy, mag;
  cv::Sobel(grey, gx, CV_32F, 1, 0);
  cv::Sobel(grey, gy, CV_32F, 0, 1);
  cv::magnitude(gx, gy, mag);
  // The image's noise level: the median gradient (most pixels of any image
  // are not on an edge). Sobel's gain is 8 per grey level a pixel.
  std::vector<float> all;
  all.reserve(mag.total() / 7 + 1);
  // Every 7th pixel of the (continuous, freshly made) magnitude image.
  const float* m0 = mag.ptr<float>();
  for (std::size_t i = 0; i < mag.total(); i += 7)
    all.push_back(m0[i]);
  auto mid = all.begin() + static_cast<std::ptrdiff_t>(all.size() / 2);
  std::nth_element(all.begin(), mid, all.end());
  const float threshold = std::max(3.0F * *mid, 8.0F);
  std::vector<cv::Point2f> pixels;
  std::vector<float> z;
  for (int y0 = 1; y0 + cellPx <= grey.rows - 1; y0 += cellPx)
    for (int x0 = 1; x0 + cellPx <= grey.cols - 1; x0 += cellPx)
    {
      float best = threshold;
      cv::Point bestAt(-1, -1);
      for (int y = y0; y < y0 + cellPx; ++y)
      {
        const float* m = mag.ptr<float>(y);
        for (int x = x0; x < x0 + cellPx; ++x)
        {
          if (m[x] <= best)
            continue;
          if (!(geometry::depthByRule(depth, x, y, rule) > 0))
            continue;
          best = m[x];
          bestAt = {x, y};
        }
      }
      if (bestAt.x < 0)
        continue;
      pixels.emplace_back(static_cast<float>(bestAt.x), static_cast<float>(bestAt.y));
      z.push_back(depth.at<float>(bestAt));
    }
  if (pixels.empty())
    return s;
  std::vector<cv::Point2f> normalised;
  cv::undistortPoints(pixels, normalised, K, dist);
  s.points.reserve(pixels.size());
  s.grey.reserve(pixels.size());
  for (std::size_t i = 0; i < pixels.size(); ++i)
  {
    s.points.emplace_back(normalised[i].x * z[i], normalised[i].y * z[i], z[i]);
    s.grey.push_back(grey.at<uint8_t>(pixels[i]));
  }
  return s;
}

double TPhotoComparison::z() const
{
  const double votes = static_cast<double>(firstCloser + secondCloser);
  return votes > 0 ? (static_cast<double>(secondCloser) - static_cast<double>(firstCloser)) /
                         std::sqrt(votes)
                   : 0.0;
}

TPhotoComparison comparePhotometric(
    const TPhotoSamples& samples, const cv::Mat& grey, const cv::Mat& K, const cv::Mat& dist,
    const TRigid& first, const TRigid& second)
{
  TPhotoComparison c;
  if (samples.points.empty() || grey.empty() || grey.type() != CV_8UC1)
    return c;
  const auto a = differences(samples, grey, K, dist, first);
  const auto b = differences(samples, grey, K, dist, second);
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    if (a[i] < 0 || b[i] < 0)
      continue;
    ++c.compared;
    if (a[i] < b[i])
      ++c.firstCloser;
    else if (b[i] < a[i])
      ++c.secondCloser;
  }
  return c;
}
}  // namespace roislam::frontend::detail
