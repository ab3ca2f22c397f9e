#include "WorkingResolution.h"

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "FlowTracking.h"

namespace roislam::frontend::detail
{
int featureShift(const cv::Size& image, bool automatic)
{
  return automatic ? flowShift(image) : 0;
}

cv::Mat reduced(const cv::Mat& grey, int shift)
{
  cv::Mat out = grey;
  for (int i = 0; i < shift; ++i)
    cv::pyrDown(out, out);
  return out;
}

TWorkingImage workingImage(const cv::Mat& grey, bool automatic)
{
  const int shift = featureShift(grey.size(), automatic);
  return {reduced(grey, shift), shift, grey.size()};
}

std::vector<cv::Mat> flowPyramidOf(
    const cv::Mat& grey, const TWorkingImage& w, const TFlowParams& p, bool withDerivatives)
{
  return w.shift == flowShift(grey.size()) ? flowPyramidOfTracked(w.grey, p, withDerivatives)
                                           : flowPyramid(grey, p, withDerivatives);
}

void toImagePixels(features::TFeatureSet& set, int shift)
{
  if (shift == 0)
    return;
  const float s = static_cast<float>(1 << shift);
  for (cv::KeyPoint& k : set.keypoints)
  {
    k.pt = fromFlowLevel(k.pt, shift);
    k.size *= s;
  }
}

cv::Rect scaledOutwards(const cv::Rect& r, double scale)
{
  const int x0 = static_cast<int>(std::floor(r.x * scale));
  const int y0 = static_cast<int>(std::floor(r.y * scale));
  const int x1 = static_cast<int>(std::ceil(r.br().x * scale));
  const int y1 = static_cast<int>(std::ceil(r.br().y * scale));
  return cv::Rect(x0, y0, x1 - x0, y1 - y0);
}

features::TFeatureSet extractIn(
    const features::CFeatureExtractor& e, const TWorkingImage& w, const cv::Rect& region, int cap,
    std::size_t* pixels)
{
  if (w.shift == 0)
    return e.extractIn(w.grey, region, cap, pixels);
  // The region at the working level, rounded outwards (pixel centres: the
  // camera's pixel u covers the level's [(u - o) / s - 0.5 / s, ...]).
  features::TFeatureSet found = e.extractIn(
      w.grey, scaledOutwards(region, 1.0 / static_cast<double>(1 << w.shift)), cap, pixels);
  toImagePixels(found, w.shift);
  std::vector<int> keep;
  const cv::Rect2f box(region);
  for (std::size_t i = 0; i < found.size(); ++i)
    if (box.contains(found.keypoints[i].pt))
      keep.push_back(static_cast<int>(i));
  if (keep.size() == found.size())
    return found;
  return found.select(keep);
}
}  // namespace roislam::frontend::detail
