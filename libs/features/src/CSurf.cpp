/* SURF detector and descriptor (Bay et al., CVIU 2008), written from the paper.
 * Pipeline: grey 8-bit image -> integral image -> Fast-Hessian keypoints
 * (surf_FastHessian) -> cap to the strongest -> orientation and descriptor
 * (surf_Descriptor). */
#include <roislam/features/CSurf.h>

#include <algorithm>
#include <cmath>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>

#include "surf_Descriptor.h"
#include "surf_FastHessian.h"
#include "surf_Integral.h"

namespace roislam::features
{
namespace
{
void validate(const CSurf::TParams& p)
{
  if (!std::isfinite(p.hessianThreshold) || p.hessianThreshold < 0)
    throw std::invalid_argument(
        "CSurf: hessianThreshold must be a finite value >= 0 (got " +
        std::to_string(p.hessianThreshold) + ")");
  if (p.nOctaves < 1 || p.nOctaves > 10)
    throw std::invalid_argument(
        "CSurf: nOctaves must be in [1, 10] (got " + std::to_string(p.nOctaves) + ")");
  if (p.nOctaveLayers < 1 || p.nOctaveLayers > 20)
    throw std::invalid_argument(
        "CSurf: nOctaveLayers must be in [1, 20] (got " + std::to_string(p.nOctaveLayers) + ")");
  if (p.maxFeatures < 0)
    throw std::invalid_argument(
        "CSurf: maxFeatures must be >= 0, 0 = no cap (got " + std::to_string(p.maxFeatures) + ")");
}

cv::Mat toGrey8(const cv::Mat& img)
{
  if (img.depth() != CV_8U)
    throw std::invalid_argument(
        "CSurf: image must be 8-bit (CV_8UC1/3/4), got type " + std::to_string(img.type()));
  switch (img.channels())
  {
    case 1:
      return img;
    case 3:
    {
      cv::Mat g;
      cv::cvtColor(img, g, cv::COLOR_BGR2GRAY);
      return g;
    }
    case 4:
    {
      cv::Mat g;
      cv::cvtColor(img, g, cv::COLOR_BGRA2GRAY);
      return g;
    }
    default:
      throw std::invalid_argument(
          "CSurf: image must have 1, 3 or 4 channels, got " + std::to_string(img.channels()));
  }
}

/** Strongest first; ties broken by position and size so the order (and thus
 *  the capped set) is deterministic. */
bool stronger(const cv::KeyPoint& a, const cv::KeyPoint& b)
{
  if (a.response != b.response)
    return a.response > b.response;
  if (a.pt.y != b.pt.y)
    return a.pt.y < b.pt.y;
  if (a.pt.x != b.pt.x)
    return a.pt.x < b.pt.x;
  return a.size < b.size;
}
}  // namespace

CSurf::CSurf(const TParams& params) : m_params(params)
{
  validate(m_params);
}

cv::Ptr<CSurf> CSurf::create(const TParams& params)
{
  return cv::makePtr<CSurf>(params);
}
cv::Ptr<CSurf> CSurf::create()
{
  return cv::makePtr<CSurf>(TParams());
}

void CSurf::detectAndCompute(
    cv::InputArray image, cv::InputArray mask, std::vector<cv::KeyPoint>& keypoints,
    cv::OutputArray descriptors, bool useProvidedKeypoints)
{
  const cv::Mat img = image.getMat();
  const cv::Mat msk = mask.getMat();
  if (!msk.empty() && (msk.type() != CV_8UC1 || msk.size() != img.size()))
    throw std::invalid_argument("CSurf: mask must be CV_8UC1 and of the image's size");
  if (img.empty())
  {
    if (!useProvidedKeypoints)
      keypoints.clear();
    if (descriptors.needed())
      descriptors.release();
    return;
  }
  const surf::TIntegral integral(toGrey8(img));

  if (!useProvidedKeypoints)
  {
    surf::TFastHessianParams fh;
    fh.threshold = m_params.hessianThreshold;
    fh.nOctaves = m_params.nOctaves;
    fh.nOctaveLayers = m_params.nOctaveLayers;
    keypoints = surf::detectFastHessian(integral, fh);
    if (!msk.empty())
    {
      keypoints.erase(
          std::remove_if(
              keypoints.begin(), keypoints.end(),
              [&](const cv::KeyPoint& kp)
              {
                const int x = std::clamp(static_cast<int>(std::lround(kp.pt.x)), 0, msk.cols - 1);
                const int y = std::clamp(static_cast<int>(std::lround(kp.pt.y)), 0, msk.rows - 1);
                return msk.at<uint8_t>(y, x) == 0;
              }),
          keypoints.end());
    }
    // Cap before orientation/description so dropped keypoints cost nothing.
    std::sort(keypoints.begin(), keypoints.end(), stronger);
    if (m_params.maxFeatures > 0 && keypoints.size() > static_cast<size_t>(m_params.maxFeatures))
      keypoints.resize(static_cast<size_t>(m_params.maxFeatures));
  }
  else
  {
    for (auto& kp : keypoints)
    {
      if (!(kp.size > 0))
        throw std::invalid_argument("CSurf: provided keypoint with size <= 0");
      kp.class_id = surf::laplacianSign(integral, kp);
    }
  }

  const bool describeToo = descriptors.needed();
  const int dim = descriptorSize();
  cv::Mat desc;
  if (describeToo)
  {
    descriptors.create(static_cast<int>(keypoints.size()), dim, CV_32F);
    desc = descriptors.getMat();
  }
  const bool upright = m_params.upright, extended = m_params.extended;
  cv::parallel_for_(
      cv::Range(0, static_cast<int>(keypoints.size())),
      [&](const cv::Range& r)
      {
        for (int k = r.start; k < r.end; ++k)
        {
          cv::KeyPoint& kp = keypoints[k];
          kp.angle = upright ? 0.0f : surf::dominantOrientation(integral, kp);
          if (describeToo)
            surf::describe(integral, kp, upright, extended, desc.ptr<float>(k));
        }
      });
}
}  // namespace roislam::features
