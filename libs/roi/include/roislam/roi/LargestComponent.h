/* The largest 8-connected component of a binary mask, by run-length
 * labelling: rows become runs of foreground pixels, overlapping runs of
 * adjacent rows are joined (union-find), and areas and bounding boxes are
 * summed per component. Stage 1 needs only this one component; after the
 * edge-growing morphology its masks are a few large blobs, i.e. few runs, and
 * this costs a fraction of cv::connectedComponentsWithStats, which labels and
 * measures every pixel (0.81 ms against 0.05 ms on fr1 masks here, one thread).
 */
#pragma once

#include <opencv2/core.hpp>
#include <optional>

namespace roislam::roi
{
struct TComponent
{
  cv::Rect box;
  /** Foreground pixels of the component. */
  int area = 0;
};

/** Largest component of `mask` (CV_8UC1, non-zero = foreground), nullopt
 *  when it has no foreground. Of equally large components, the one whose
 *  first pixel comes first in raster order. Throws std::invalid_argument on
 *  another type. */
std::optional<TComponent> largestComponent(const cv::Mat& mask);
}  // namespace roislam::roi
