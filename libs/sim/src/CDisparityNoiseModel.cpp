#include "roislam/sim/CDisparityNoiseModel.h"

#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace roislam::sim
{
void CDisparityNoiseModel::corruptDepth(cv::Mat& depth, mrpt::random::CRandomGenerator& rng) const
{
  CV_Assert(depth.type() == CV_32FC1);
  // One fast OpenCV stream seeded from the MRPT one (as CKinectNoiseModel).
  const uint64_t seed =
      (static_cast<uint64_t>(rng.drawUniform32bit()) << 32) | rng.drawUniform32bit();
  cv::RNG cvRng(seed);
  cv::Mat mapX(depth.size(), CV_32FC1), mapY(depth.size(), CV_32FC1), n(depth.size(), CV_32FC1);
  cvRng.fill(mapX, cv::RNG::NORMAL, 0.0, m_p.lateral_sigma_px);
  cvRng.fill(mapY, cv::RNG::NORMAL, 0.0, m_p.lateral_sigma_px);
  cvRng.fill(n, cv::RNG::NORMAL, 0.0, m_p.disparity_noise_steps);
  for (int r = 0; r < depth.rows; ++r)
  {
    auto* x = mapX.ptr<float>(r);
    auto* y = mapY.ptr<float>(r);
    for (int c = 0; c < depth.cols; ++c)
    {
      x[c] += static_cast<float>(c);
      y[c] += static_cast<float>(r);
    }
  }
  cv::Mat linear, nearest, valid, validLinear;
  cv::remap(depth, linear, mapX, mapY, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  cv::remap(depth, nearest, mapX, mapY, cv::INTER_NEAREST, cv::BORDER_REPLICATE);
  cv::Mat(depth > 0).convertTo(valid, CV_32FC1, 1.0 / 255);
  cv::remap(valid, validLinear, mapX, mapY, cv::INTER_LINEAR, cv::BORDER_REPLICATE);

  const double bf = m_p.disparity_bf, steps = m_p.disparity_steps_per_px;
  for (int r = 0; r < depth.rows; ++r)
  {
    float* d = depth.ptr<float>(r);
    const float* l = linear.ptr<float>(r);
    const float* nn = nearest.ptr<float>(r);
    const float* v = validLinear.ptr<float>(r);
    const float* g = n.ptr<float>(r);
    for (int c = 0; c < depth.cols; ++c)
    {
      // A lookup that touches no reading keeps the nearest sample (which may
      // itself be no reading): bilinear weights on 0 would invent depths.
      const float z = v[c] > 0.999f ? l[c] : nn[c];
      if (!(z > 0))
      {
        d[c] = 0;
        continue;
      }
      const double disparitySteps = std::round(bf / z * steps + g[c]);
      d[c] = disparitySteps > 0 ? static_cast<float>(bf * steps / disparitySteps) : 0.0f;
    }
  }
}
}  // namespace roislam::sim
