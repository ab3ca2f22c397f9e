#include "roislam/io/CameraAxes.h"

#include <cmath>
#include <opencv2/core.hpp>

namespace roislam::io
{
bool hasNegativeFocalLength(const mrpt::img::TCamera& camera)
{
  return camera.fx() < 0 || camera.fy() < 0;
}

mrpt::img::TCamera withPositiveFocalLengths(const mrpt::img::TCamera& camera)
{
  if (!hasNegativeFocalLength(camera))
    return camera;
  mrpt::img::TCamera c = camera;
  // Flipping the columns maps u to ncols - 1 - u, so u = fx x_d + cx becomes
  // |fx| x_d + (ncols - 1 - cx) with the same normalised (distorted)
  // coordinate x_d: the optical frame and the distortion stay as they are.
  // Rows alike.
  const double cx =
      camera.fx() < 0 ? static_cast<double>(camera.ncols) - 1 - camera.cx() : camera.cx();
  const double cy =
      camera.fy() < 0 ? static_cast<double>(camera.nrows) - 1 - camera.cy() : camera.cy();
  c.setIntrinsicParamsFromValues(std::abs(camera.fx()), std::abs(camera.fy()), cx, cy);
  return c;
}

void flipToPositiveFocalLengths(cv::Mat& image, const mrpt::img::TCamera& declared)
{
  const bool cols = declared.fx() < 0, rows = declared.fy() < 0;
  if (image.empty() || (!cols && !rows))
    return;
  // cv::flip codes: 0 about the x axis (rows), 1 about the y axis (columns), -1 both.
  cv::Mat flipped;
  cv::flip(image, flipped, rows && cols ? -1 : (rows ? 0 : 1));
  image = flipped;
}

}  // namespace roislam::io
