/* Private: the rolling-shutter model of the front end.
 *
 * A Kinect-type colour camera exposes its rows one after the other, top to
 * bottom, so while the camera moves each row sees the scene from a slightly
 * different pose. On fr1/rpy (about 60 deg/s) this was the largest error left
 * in a frame-to-keyframe registration: the global-shutter motion that best
 * explains the sheared image is wrong by up to a degree, and the translation
 * follows it by centimetres. rectifyRollingShutter() moves every keypoint's
 * point (and so its pixel) by the motion the camera made between its row's
 * time and the middle row's, so the set looks as if taken at once at the
 * middle row's time. The depth image, registered to the colour one, is read
 * at the keypoint's own pixel (its rows are read out in step, to first order).
 * The velocity comes from the odometry itself (CRgbdOdometry.cpp).
 */
#pragma once

#include <mrpt/poses/CPose3D.h>
#include <roislam/frontend/TKeyframe.h>
#include <roislam/geometry/KeypointLifting.h>

#include <Eigen/Dense>
#include <cstddef>
#include <opencv2/core.hpp>
#include <vector>

#include "FeatureLifting.h"
#include "ReprojectionRefinement.h"

namespace roislam::frontend::detail
{
/** A point seen s seconds after the middle row (its raw undistorted pixel and
 *  depth), carried into the middle row's camera: exp(omega s) X + linear s. */
Eigen::Vector3d rectifyPoint(
    const cv::Point2f& rawPixel, double rawZ, double s, const TCameraRate& rate,
    const TPinhole& pinhole);

/** Recomputes lifted.undistorted and lifted.z at the valid indices from the
 *  raw ones: a point seen s = rowFraction * readout_s seconds after the
 *  middle row is carried into the middle row's camera, X' = exp(omega s) X +
 *  linear s, and its pixel is X' projected. A zero rate or readout_s = 0
 *  restores the raw values. Records `rate` as lifted.rate either way. */
void rectifyRollingShutter(
    TLiftedFeatures& lifted, const TCameraRate& rate, double readout_s, const TPinhole& pinhole);

/** Depth taken dt seconds after the colour image (its stamp minus the
 *  colour's; a Kinect v1 streams them unsynchronised): the depth image saw
 *  each point from where the camera was then. For every valid keypoint of
 *  `lifted` (lifted from the same depth image), its point as first read
 *  (readZ) is carried to the depth's time with `rate`, its depth is read
 *  where it was then (the project's depth rule, at that distorted pixel) and
 *  carried back to the colour's time: rawZ becomes the depth along the
 *  keypoint's own ray at the colour's time. A keypoint whose depth-time pixel
 *  has no depth by the rule is dropped from valid (dropUnread) or keeps its
 *  rawZ. dt = 0 or a zero rate restores readZ. Runs before
 *  rectifyRollingShutter (which starts from rawZ). */
void alignDepthTime(
    TLiftedFeatures& lifted, const cv::Mat& depth, const cv::Mat& K, const cv::Mat& dist,
    const geometry::TDepthRule& rule, const TPinhole& pinhole, const TCameraRate& rate, double dt,
    bool dropUnread);

/** liftFeatures() of `set` with the frame's depth image, then
 *  alignDepthTime() with the frame's depth offset dt and `rate` (dropUnread). */
TLiftedFeatures liftAtColourTime(
    const features::TFeatureSet& set, const cv::Mat& depth, const cv::Mat& K, const cv::Mat& dist,
    const TPinhole& pinhole, const CRgbdOdometry::TOptions& o, const TCameraRate& rate, double dt);

/** alignDepthTime() again with a better rate, keeping the valid set (a
 *  registration's matches index it). */
void realignDepthTime(
    TLiftedFeatures& lifted, const cv::Mat& depth, const cv::Mat& K, const cv::Mat& dist,
    const TPinhole& pinhole, const CRgbdOdometry::TOptions& o, const TCameraRate& rate, double dt);

/** The camera's velocity during a motion that took dt seconds (motion maps
 *  the later camera into the earlier one); zero when dt <= 0 or the motion is
 *  no hand-held camera's (see the .cpp). */
TCameraRate cameraRate(const mrpt::poses::CPose3D& motion, double dt);

/** A keyframe's raw points, kept until a velocity is known to correct them:
 *  entry j belongs to the keyframe's feature j. */
struct TUncorrectedKeyframe
{
  std::size_t id = 0;
  std::vector<cv::Point2f> rawPixels;
  std::vector<float> rawZ, rowFraction;
};

/** The raw points of the keyframe id whose features are lifted's at idx. */
TUncorrectedKeyframe uncorrectedKeyframe(
    std::size_t id, const TLiftedFeatures& lifted, const std::vector<int>& idx);

/** Replaces k's points and pixels with u's raw ones corrected with rate,
 *  and its velocity with rate. */
void correctKeyframe(
    TKeyframe& k, const TUncorrectedKeyframe& u, const TCameraRate& rate, double readout_s,
    const TPinhole& pinhole);
}  // namespace roislam::frontend::detail
