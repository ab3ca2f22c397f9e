/* SURF orientation and descriptor (Bay et al. 2008, section 4). Private to CSurf. */
#include "surf_Descriptor.h"

#include <array>
#include <cmath>
#include <vector>

namespace roislam::features::surf
{
namespace
{
constexpr float kPi = 3.14159265358979f;

/** Orientation samples: integer offsets (in units of s) within radius 6 and
 *  their Gaussian weights (sigma 2s), computed once. */
struct TOrientationSamples
{
  std::vector<int> di, dj;
  std::vector<float> w;
  TOrientationSamples()
  {
    for (int i = -6; i <= 6; ++i)
      for (int j = -6; j <= 6; ++j)
        if (i * i + j * j < 36)
        {
          di.push_back(i);
          dj.push_back(j);
          w.push_back(std::exp(-static_cast<float>(i * i + j * j) / (2.0f * 2.0f * 2.0f)));
        }
  }
};

/** Descriptor samples: a 20 x 20 grid at spacing s centred on the keypoint,
 *  Gaussian weights sigma 3.3s, computed once. */
struct TDescriptorWeights
{
  std::array<float, 20> coord{};
  std::array<float, 400> w{};
  TDescriptorWeights()
  {
    for (int k = 0; k < 20; ++k)
      coord[k] = static_cast<float>(k) - 9.5f;
    for (int v = 0; v < 20; ++v)
      for (int u = 0; u < 20; ++u)
        w[v * 20 + u] =
            std::exp(-(coord[u] * coord[u] + coord[v] * coord[v]) / (2.0f * 3.3f * 3.3f));
  }
};

const TOrientationSamples& orientationSamples()
{
  static const TOrientationSamples s;
  return s;
}
const TDescriptorWeights& descriptorWeights()
{
  static const TDescriptorWeights s;
  return s;
}

}  // namespace

float dominantOrientation(const TIntegral& in, const cv::KeyPoint& kp)
{
  const float s = keypointScale(kp);
  const TOrientationSamples& S = orientationSamples();
  // Responses binned by angle (1 degree bins); a window of 60 bins = pi/3
  // slides over them one bin at a time.
  constexpr int kBins = 360, kWindow = 60;
  std::array<float, kBins> bx{}, by{};
  for (size_t k = 0; k < S.w.size(); ++k)
  {
    float dx, dy;
    // Wavelet side 4s.
    in.haarAt(kp.pt.x + S.dj[k] * s, kp.pt.y + S.di[k] * s, 2.0f * s, dx, dy);
    dx *= S.w[k];
    dy *= S.w[k];
    if (dx == 0 && dy == 0)
      continue;
    float a = std::atan2(dy, dx);
    if (a < 0)
      a += 2 * kPi;
    int bin = static_cast<int>(a * (kBins / (2 * kPi)));
    if (bin >= kBins)
      bin = kBins - 1;
    bx[bin] += dx;
    by[bin] += dy;
  }
  float sx = 0, sy = 0;
  for (int b = 0; b < kWindow; ++b)
  {
    sx += bx[b];
    sy += by[b];
  }
  float best = -1, bestX = 0, bestY = 0;
  for (int start = 0; start < kBins; ++start)
  {
    const float m = sx * sx + sy * sy;
    if (m > best)
    {
      best = m;
      bestX = sx;
      bestY = sy;
    }
    const int out = start, in2 = (start + kWindow) % kBins;
    sx += bx[in2] - bx[out];
    sy += by[in2] - by[out];
  }
  if (best <= 0)
    return 0.0f;
  float deg = std::atan2(bestY, bestX) * (180.0f / kPi);
  if (deg < 0)
    deg += 360.0f;
  if (deg >= 360.0f)
    deg -= 360.0f;
  return deg;
}

void describe(const TIntegral& in, const cv::KeyPoint& kp, bool upright, bool extended, float* out)
{
  const float s = keypointScale(kp);
  const TDescriptorWeights& W = descriptorWeights();
  float co = 1, si = 0;
  if (!upright && kp.angle >= 0)
  {
    const float a = kp.angle * (kPi / 180.0f);
    co = std::cos(a);
    si = std::sin(a);
  }
  const int dim = extended ? 128 : 64;
  std::fill(out, out + dim, 0.0f);
  for (int v = 0; v < 20; ++v)
  {
    const float cv_ = W.coord[v] * s;
    for (int u = 0; u < 20; ++u)
    {
      const float cu = W.coord[u] * s;
      // Sample position: (u, v) in the keypoint frame, rotated into the image.
      const float px = kp.pt.x + cu * co - cv_ * si;
      const float py = kp.pt.y + cu * si + cv_ * co;
      float dx, dy;
      in.haarAt(px, py, s, dx, dy);  // wavelet side 2s
      const float w = W.w[v * 20 + u];
      // Responses relative to the keypoint orientation.
      const float rx = w * (dx * co + dy * si);
      const float ry = w * (-dx * si + dy * co);
      float* d = out + ((v / 5) * 4 + (u / 5)) * (extended ? 8 : 4);
      if (!extended)
      {
        d[0] += rx;
        d[1] += ry;
        d[2] += std::abs(rx);
        d[3] += std::abs(ry);
      }
      else
      {
        // Sums of dx, |dx| split by the sign of dy, and of dy, |dy| by dx.
        if (ry < 0)
        {
          d[0] += rx;
          d[1] += std::abs(rx);
        }
        else
        {
          d[2] += rx;
          d[3] += std::abs(rx);
        }
        if (rx < 0)
        {
          d[4] += ry;
          d[5] += std::abs(ry);
        }
        else
        {
          d[6] += ry;
          d[7] += std::abs(ry);
        }
      }
    }
  }
  float norm = 0;
  for (int k = 0; k < dim; ++k)
    norm += out[k] * out[k];
  if (norm > 0)
  {
    const float inv = 1.0f / std::sqrt(norm);
    for (int k = 0; k < dim; ++k)
      out[k] *= inv;
  }
}
}  // namespace roislam::features::surf
