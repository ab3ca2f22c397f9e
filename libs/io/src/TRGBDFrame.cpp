#include "roislam/io/TRGBDFrame.h"

#include <opencv2/imgproc.hpp>

namespace roislam::io
{
cv::Mat TRGBDFrame::grey() const
{
  cv::Mat out;
  if (rgb.empty())
    return out;
  if (rgb.channels() == 1)
    out = rgb.clone();
  else if (rgb.channels() == 4)
    cv::cvtColor(rgb, out, cv::COLOR_BGRA2GRAY);
  else
    cv::cvtColor(rgb, out, cv::COLOR_BGR2GRAY);
  return out;
}
}  // namespace roislam::io
