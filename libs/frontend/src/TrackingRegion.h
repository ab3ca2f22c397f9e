/* Private: the tracking region of the ROI modes (roi_extraction = region):
 * the ROI grown to track with, the reference keyframe's region followed into
 * the current frame, and the rest of the image as bands for the extension.
 */
#pragma once

#include <mrpt/poses/CPose3D.h>
#include <roislam/frontend/TKeyframe.h>

#include <opencv2/core/types.hpp>
#include <vector>

#include "ReprojectionRefinement.h"

namespace roislam::frontend::detail
{
/** The ROI grown about its centre to a minimum share of the image and a
 *  minimum aspect (short side / long side), moved inside the image. */
cv::Rect trackingRegion(
    const cv::Rect& roi, const cv::Size& image, double minArea, double minAspect);

/** The reference keyframe's tracking region as this frame should see it:
 *  its corners, at the region's median depth, moved by the predicted motion
 *  (pose of the frame relative to the keyframe) and projected. Empty when it
 *  leaves the image. */
cv::Rect followRegion(
    const TKeyframe& kf, const mrpt::poses::CPose3D& predictedRel, const TPinhole& cam,
    const cv::Size& image);

/** The image outside `region`, as up to four bands (above, below, left,
 *  right), which together cover every pixel once. */
std::vector<cv::Rect> outside(const cv::Rect& region, const cv::Size& image);
}  // namespace roislam::frontend::detail
