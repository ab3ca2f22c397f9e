/* Private: a third opinion where the features and depth ICP disagree
 * (refineWithDepth, icp_fusion = measured).
 *
 * IcpConsistency books every disagreement between the two against ICP: it
 * takes the features' covariance as honest. Where features are plentiful
 * that holds (fr1: ICP is the biased one, its depth neither captured with
 * the colour nor free of distortion). In a featureless room it does not: a
 * handful of features on shading edges registers 25-49 mm off while
 * claiming 1.3-5 mm, and depth ICP, right to half a millimetre, is scaled
 * away (README "The reference odometry where ICP is well constrained").
 * The two disagreements have the same size, so their statistics cannot
 * tell which estimate is wrong. The colour image can: the trajectory is
 * the colour camera's, and the right pose carries the keyframe's image
 * onto the current one.
 *
 * The keyframe keeps grey levels and 3-D points of its strongest-gradient
 * pixels (one per grid cell, away from depth edges, where a pixel's depth
 * is ambiguous); each estimate warps them into the current image; a sign
 * test over the samples says which estimate puts more of them closer to
 * their grey level. A sign test, not a cost ratio: it is blind to how
 * large the residuals are (exposure, noise, blur), so it needs no scale.
 */
#pragma once

#include <roislam/geometry/KeypointLifting.h>

#include <Eigen/Core>
#include <cstddef>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "RigidMath.h"

namespace roislam::frontend::detail
{
struct TPhotoSamples
{
  /** Keyframe optical frame, metres. */
  std::vector<Eigen::Vector3d> points;
  /** The keyframe's grey level at each point's pixel. */
  std::vector<float> grey;
};

/** A keyframe's samples: in each cell of cellPx x cellPx pixels, the pixel
 *  of strongest grey gradient, if that gradient stands out of the image's
 *  noise (3x the median gradient magnitude, at least 1 grey level a pixel)
 *  and the depth rule accepts its depth (geometry::depthByRule: in range,
 *  off depth edges). grey CV_8UC1 and depth CV_32FC1 (metres) at the
 *  camera's resolution; K, dist its intrinsics (OpenCV's). */
TPhotoSamples photoSamples(
    const cv::Mat& grey, const cv::Mat& depth, const cv::Mat& K, const cv::Mat& dist,
    const geometry::TDepthRule& rule, int cellPx = 12);

/** How two estimates of the current frame's pose in the keyframe
 *  (TRegistration::T's convention: x_keyframe = T x_current) carry the
 *  keyframe's samples onto the current grey image. Per sample seen by both
 *  inside the image, the absolute grey difference under each pose, after
 *  the median difference under that pose (a common exposure change) is
 *  removed; the closer one gets the sample's vote (ties none). */
struct TPhotoComparison
{
  std::size_t compared = 0, firstCloser = 0, secondCloser = 0;
  /** The sign test's z: (secondCloser - firstCloser) / sqrt(votes); > 0
   *  favours the second estimate; 0 without votes. */
  double z() const;
};
TPhotoComparison comparePhotometric(
    const TPhotoSamples& samples, const cv::Mat& grey, const cv::Mat& K, const cv::Mat& dist,
    const TRigid& first, const TRigid& second);
}  // namespace roislam::frontend::detail
