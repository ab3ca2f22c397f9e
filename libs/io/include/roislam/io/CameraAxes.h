/* Cameras whose pixel axes run against their optical frame's axes: a negative
 * focal length. ICL-NUIM publishes fy = -480: its ground truth is the path of
 * a camera frame whose y axis points up while the image rows, as stored, run
 * down. Calibrated with fy > 0 instead, the same images give the mirror image
 * of that path, which no rigid (or similarity) alignment maps onto the ground
 * truth: on a synthetic ICL-like loop with y-up ground truth, ATE 0.105 m
 * instead of 0.006 m (README "Sensor description").
 *
 * Every algorithm of ours assumes positive focal lengths, so the frame
 * sources (CTumFrameSource, observationToFrame) turn such a camera into an
 * equivalent one before anything else sees the frame: the image is flipped
 * along each axis whose focal length is negative, and the camera becomes
 * withPositiveFocalLengths(): |f| and the principal point mirrored (c' =
 * size - 1 - c); the distortion, a function of the normalised coordinates,
 * is unchanged. A pixel of the flipped image and its new intrinsics
 * unproject to exactly the 3-D point the original pixel and intrinsics give,
 * in the same optical frame, so
 * poses, trajectories and maps stay in the declared camera's convention and
 * compare directly with its ground truth; only pixel coordinates (ROI boxes,
 * saved patches) refer to the flipped image. The depth-to-colour extrinsics
 * are unchanged for the same reason.
 */
#pragma once

#include <mrpt/img/TCamera.h>

#include <opencv2/core/mat.hpp>

namespace roislam::io
{
/** True when fx < 0 or fy < 0. */
bool hasNegativeFocalLength(const mrpt::img::TCamera& camera);

/** The same camera with positive focal lengths, for images flipped by
 *  flipToPositiveFocalLengths(): |fx|, |fy|; cx -> ncols - 1 - cx when fx < 0,
 *  cy -> nrows - 1 - cy when fy < 0; distortion unchanged. A camera with
 *  positive focal lengths is returned unchanged. */
mrpt::img::TCamera withPositiveFocalLengths(const mrpt::img::TCamera& camera);

/** Flips `image` (any type, the camera's size) in place along the axes whose
 *  focal length is negative in `declared`; nothing when both are positive. */
void flipToPositiveFocalLengths(cv::Mat& image, const mrpt::img::TCamera& declared);

}  // namespace roislam::io
