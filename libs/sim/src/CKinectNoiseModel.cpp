#include "roislam/sim/CKinectNoiseModel.h"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace roislam::sim
{
double CKinectNoiseModel::depthSigma(double z) const
{
  return m_p.sigmaA + m_p.sigmaB * (z - m_p.sigmaZ0) * (z - m_p.sigmaZ0);
}

void CKinectNoiseModel::corruptDepth(cv::Mat& depth, mrpt::random::CRandomGenerator& rng) const
{
  CV_Assert(depth.type() == CV_32FC1);
  // Discontinuities are found on the clean image (3x3 max/min, edges of the
  // image replicate), then noise is added to the surviving pixels.
  const cv::Mat kernel = cv::Mat::ones(3, 3, CV_8U);
  cv::Mat hi, lo;
  cv::dilate(depth, hi, kernel, {-1, -1}, 1, cv::BORDER_REPLICATE);
  cv::erode(depth, lo, kernel, {-1, -1}, 1, cv::BORDER_REPLICATE);
  // Standard normal draws for every pixel from OpenCV's fast generator, seeded
  // from the MRPT stream: the result depends only on the generator state.
  const uint64_t seed =
      (static_cast<uint64_t>(rng.drawUniform32bit()) << 32) | rng.drawUniform32bit();
  cv::RNG cvRng(seed);
  cv::Mat n(depth.size(), CV_32FC1);
  cvRng.fill(n, cv::RNG::NORMAL, 0.0, 1.0);
  const float ratio = static_cast<float>(m_p.edgeJumpRatio);
  for (int r = 0; r < depth.rows; ++r)
  {
    float* d = depth.ptr<float>(r);
    const float* h = hi.ptr<float>(r);
    const float* l = lo.ptr<float>(r);
    const float* g = n.ptr<float>(r);
    for (int c = 0; c < depth.cols; ++c)
    {
      const float z = d[c];
      if (z <= 0)
        continue;
      const bool edge = l[c] <= 0 || h[c] - z > ratio * z || z - l[c] > ratio * z;
      d[c] = edge ? 0.0f : std::max(1e-4f, z + g[c] * static_cast<float>(depthSigma(z)));
    }
  }
}

void CKinectNoiseModel::corruptColour(cv::Mat& rgb, mrpt::random::CRandomGenerator& rng) const
{
  CV_Assert(rgb.type() == CV_8UC3);
  if (m_p.rgbNoiseStd <= 0)
    return;
  // Same seeding scheme as corruptDepth.
  const uint64_t seed =
      (static_cast<uint64_t>(rng.drawUniform32bit()) << 32) | rng.drawUniform32bit();
  cv::RNG cvRng(seed);
  cv::Mat noise(rgb.size(), CV_16SC3);
  cvRng.fill(noise, cv::RNG::NORMAL, 0.0, m_p.rgbNoiseStd);
  cv::Mat sum;
  cv::add(rgb, noise, sum, cv::noArray(), CV_16SC3);
  sum.convertTo(rgb, CV_8UC3);
}

void CKinectNoiseModel::applyRange(cv::Mat& depth, double minDepth, double maxDepth)
{
  CV_Assert(depth.type() == CV_32FC1);
  depth.setTo(0, (depth < minDepth) | (depth > maxDepth));
}
}  // namespace roislam::sim
