/* A colour camera's lens distortion for the renders (CRgbdSimulator's
 * colour_dist): OpenGL renders a pinhole, so a distorted image is resampled
 * from a pinhole render. The pinhole is zoomed out about the principal point
 * when the distorted image sees more than the pinhole of its focal lengths
 * (barrel distortion), so that every distorted pixel finds its content.
 * Private to the simulator. */
#pragma once

#include <mrpt/math/CMatrixDynamic.h>

#include <array>
#include <opencv2/core.hpp>
#include <optional>
#include <string>

namespace roislam::sim::detail
{
/** OpenCV's (and TCamera's) first five: k1 k2 p1 p2 k3. */
using TDistortion = std::array<double, 5>;

/** "[k1 k2 p1 p2 k3]" (brackets optional; fewer values leave the rest 0);
 *  nothing when it is not numbers. */
std::optional<TDistortion> parseDistortion(const std::string& text);

bool isZero(const TDistortion& d);

/** Normalised undistorted (x, y) -> normalised distorted, OpenCV's model. */
cv::Point2d distortNormalised(const TDistortion& d, cv::Point2d p);

/** Where each pixel of a distorted W x H image of the pinhole fx, fy, cx, cy
 *  finds its content in a pinhole render of focal lengths fx / zoom,
 *  fy / zoom and the same principal point. */
struct TDistortionMap
{
  double zoom = 1;  //!< >= 1
  /** Per supersampled output pixel (W ss x H ss): its source in the
   *  supersampled render, for cv::remap. */
  cv::Mat ssMapX, ssMapY;
  /** Per output pixel centre (W x H, CV_32FC2): its source, in the render's
   *  output pixels (the depth's lookup). */
  cv::Mat centres;
};

/** Throws std::invalid_argument when the distortion does not map the image
 *  one to one (it folds back within the image: the model is not invertible
 *  there), or needs a zoom beyond 2. */
TDistortionMap makeDistortionMap(
    const TDistortion& d, unsigned W, unsigned H, double fx, double fy, double cx, double cy,
    unsigned ss);

/** Depth at each output pixel centre from a depth render supersampled ss x ss
 *  (m, 0 = none): inverse depth interpolated bilinearly between the four
 *  nearest samples where they lie on one plane, else the nearest sample. */
cv::Mat depthAtCentres(
    const mrpt::math::CMatrixFloat& depthSS, unsigned ss, const cv::Mat& centres);
}  // namespace roislam::sim::detail
