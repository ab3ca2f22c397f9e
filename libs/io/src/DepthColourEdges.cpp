#include "DepthColourEdges.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <opencv2/imgproc.hpp>
#include <utility>

namespace roislam::io::detail
{
namespace
{
float bilinear(const cv::Mat& m, double u, double v)
{
  const int x = static_cast<int>(u), y = static_cast<int>(v);
  const float a = static_cast<float>(u - x), b = static_cast<float>(v - y);
  const float* r0 = m.ptr<float>(y);
  const float* r1 = m.ptr<float>(y + 1);
  return (1 - b) * ((1 - a) * r0[x] + a * r0[x + 1]) + b * ((1 - a) * r1[x] + a * r1[x + 1]);
}

/** A colour image's Canny edges and the Sobel gradients they come from. */
struct TColourEdges
{
  cv::Mat edges;      //!< CV_8U, 255 on an edge
  cv::Mat dx, dy;     //!< CV_16S
  cv::Mat magnitude;  //!< CV_32F, |(dx, dy)|
};

/** Canny edges with thresholds from the image's own gradient statistics:
 *  the strongest 10 % of gradients start an edge, half that continues it
 *  (a fixed threshold would find no edge in a dim scene, clutter in a
 *  bright one). */
TColourEdges colourEdges(const cv::Mat& bgr)
{
  TColourEdges out;
  cv::Mat& dx = out.dx;
  cv::Mat& dy = out.dy;
  cv::Mat gray;
  cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
  cv::GaussianBlur(gray, gray, cv::Size(3, 3), 0);
  cv::Sobel(gray, dx, CV_16S, 1, 0, 3);
  cv::Sobel(gray, dy, CV_16S, 0, 1, 3);
  out.magnitude.create(gray.size(), CV_32F);
  for (int r = 0; r < gray.rows; ++r)
  {
    const auto* px = dx.ptr<int16_t>(r);
    const auto* py = dy.ptr<int16_t>(r);
    auto* m = out.magnitude.ptr<float>(r);
    for (int c = 0; c < gray.cols; ++c)
      m[c] = std::hypot(float(px[c]), float(py[c]));
  }
  std::vector<float> mags(out.magnitude.begin<float>(), out.magnitude.end<float>());
  const auto nth = mags.begin() + static_cast<std::ptrdiff_t>(0.9 * double(mags.size()));
  std::nth_element(mags.begin(), nth, mags.end());
  const double high = std::max(double(*nth), 40.0);
  cv::Canny(dx, dy, out.edges, 0.5 * high, high, true);
  return out;
}
}  // namespace

TSilhouettes findSilhouettes(
    const cv::Mat& depth, const mrpt::img::TCamera& camera, double minJumpM, double minJumpRatio,
    std::size_t maxPoints)
{
  // Silhouettes: the nearer side of a jump between two valid readings. Depth
  // cameras leave a band of no readings along a jump (the projector's
  // shadow, pixels that mix both surfaces), so the farther reading is looked
  // for across up to kMaxGap missing pixels; the pixel itself must be on the
  // near surface (its neighbour on the other side reads about the same).
  constexpr int kMaxGap = 8;
  std::vector<cv::Point3d> points;
  std::vector<cv::Point2d> outward;
  const auto& dc = camera;
  const double ifx = 1.0 / dc.fx(), ify = 1.0 / dc.fy();
  const auto at = [&](int r, int c)
  { return r >= 0 && c >= 0 && r < depth.rows && c < depth.cols ? depth.at<float>(r, c) : 0.0f; };
  for (int r = 1; r + 1 < depth.rows; ++r)
  {
    const float* row = depth.ptr<float>(r);
    for (int c = 1; c + 1 < depth.cols; ++c)
    {
      const float z = row[c];
      if (!(z > 0))
        continue;
      const double jump = std::max(minJumpM, minJumpRatio * z);
      for (const auto& [dr, dcol] : {std::pair(0, 1), {0, -1}, {1, 0}, {-1, 0}})
      {
        const float back = depth.at<float>(r - dr, c - dcol);
        if (!(back > 0) || std::abs(back - z) > 0.5 * jump)
          continue;
        float far = 0;
        int k = 0;
        while (!(far > 0) && k <= kMaxGap)
        {
          ++k;
          far = at(r + k * dr, c + k * dcol);
        }
        if (!(far > 0 && far - z > jump))
          continue;
        const double u = c + 0.5 * k * dcol, v = r + 0.5 * k * dr;
        points.emplace_back((u - dc.cx()) * ifx * z, (v - dc.cy()) * ify * z, z);
        outward.emplace_back(dcol, dr);
      }
    }
  }
  if (points.empty())
    return {};
  TSilhouettes out;
  const std::size_t keep = std::max<std::size_t>(maxPoints, 1);
  const double step = std::max(1.0, double(points.size()) / double(keep));
  for (double i = 0; i < double(points.size()); i += step)
  {
    out.points.push_back(points[static_cast<std::size_t>(i)]);
    out.outward.push_back(outward[static_cast<std::size_t>(i)]);
  }
  return out;
}

TEdgeField colourEdgeField(const cv::Mat& bgr)
{
  // Each edge pixel's sub-pixel place: the peak of a parabola through the
  // gradient magnitude across the edge. Canny marks one pixel of the two a
  // step lies between (OpenCV's non-maximum suppression breaks a tie
  // towards the left and the top), and a render's edges are such steps:
  // read at pixel centres, every edge sat half a pixel up and left, which
  // moved the estimated principal point by as much.
  TEdgeField out;
  const TColourEdges colour = colourEdges(bgr);
  const cv::Mat &edges = colour.edges, &dx = colour.dx, &dy = colour.dy, &mag = colour.magnitude;
  cv::Mat notEdge, distance, labels;
  cv::bitwise_not(edges, notEdge);
  cv::distanceTransform(
      notEdge, distance, labels, cv::DIST_L2, cv::DIST_MASK_5, cv::DIST_LABEL_PIXEL);
  std::vector<int> labelToEdge;
  for (int r = 1; r + 1 < edges.rows; ++r)
    for (int c = 1; c + 1 < edges.cols; ++c)
    {
      if (!edges.at<uchar>(r, c))
        continue;
      const double m0 = mag.at<float>(r, c);
      const cv::Point2d n(dx.at<int16_t>(r, c) / m0, dy.at<int16_t>(r, c) / m0);
      double offset = 0;
      if (c >= 2 && r >= 2 && c + 2 < edges.cols && r + 2 < edges.rows)
      {
        const double mMinus = bilinear(mag, c - n.x, r - n.y);
        const double mPlus = bilinear(mag, c + n.x, r + n.y);
        const double curvature = mMinus - 2 * m0 + mPlus;
        if (curvature < 0)
          offset = std::clamp(0.5 * (mMinus - mPlus) / curvature, -0.5, 0.5);
      }
      const int label = labels.at<int>(r, c);
      if (label >= static_cast<int>(labelToEdge.size()))
        labelToEdge.resize(static_cast<std::size_t>(label) + 1, -1);
      labelToEdge[static_cast<std::size_t>(label)] = static_cast<int>(out.at.size());
      out.at.emplace_back(c + offset * n.x, r + offset * n.y);
      out.normal.push_back(n);
    }
  // Labels to edge indices (-1: an edge on the border, not used).
  out.nearest.create(labels.size(), CV_32S);
  for (int r = 0; r < labels.rows; ++r)
    for (int c = 0; c < labels.cols; ++c)
    {
      const int label = labels.at<int>(r, c);
      out.nearest.at<int>(r, c) = label >= 0 && label < static_cast<int>(labelToEdge.size())
                                      ? labelToEdge[std::size_t(label)]
                                      : -1;
    }
  return out;
}
}  // namespace roislam::io::detail
