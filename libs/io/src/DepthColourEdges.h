/* The two measurements CDepthColourCalibrator fits to each other (private
 * to libs/io): the silhouettes in a depth image and the edges of a colour
 * image, each with where it lies to a fraction of a pixel. */
#pragma once

#include <mrpt/img/TCamera.h>

#include <cstddef>
#include <opencv2/core.hpp>
#include <vector>

namespace roislam::io::detail
{
/** Silhouette points of one depth image, in the depth optical frame. */
struct TSilhouettes
{
  std::vector<cv::Point3d> points;
  std::vector<cv::Point2d> outward;  //!< each one's direction to the far side (px)
};

/** The nearer side of every jump between two valid readings of `depth`
 *  (CV_32FC1 metres on `camera`'s grid) larger than max(minJumpM,
 *  minJumpRatio x depth), at most maxPoints of them, taken evenly. */
TSilhouettes findSilhouettes(
    const cv::Mat& depth, const mrpt::img::TCamera& camera, double minJumpM, double minJumpRatio,
    std::size_t maxPoints);

/** A colour image's edges, as a field that says for every pixel which edge
 *  pixel is nearest, and where each edge lies and which way it faces. */
struct TEdgeField
{
  cv::Mat nearest;                  //!< CV_32S: index of the nearest edge, -1 none
  std::vector<cv::Point2d> at;      //!< each edge's sub-pixel position
  std::vector<cv::Point2d> normal;  //!< and its unit gradient direction
};

/** The edge field of a CV_8UC3 colour image. */
TEdgeField colourEdgeField(const cv::Mat& bgr);
}  // namespace roislam::io::detail
