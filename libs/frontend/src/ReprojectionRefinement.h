/* Private: Gauss-Newton refinement of a rigid motion between two RGB-D views
 * from matched 3-D points and their (undistorted) pixels, minimising the
 * symmetric reprojection error (reference points into the current image and
 * current points into the reference image) with Huber weights. Pixels are far
 * more precise than Kinect depth, so this beats a 3-D least-squares fit.
 */
#pragma once

#include <roislam/geometry/TPinhole.h>

#include <cstddef>
#include <functional>
#include <vector>

#include "RigidMath.h"

namespace roislam::frontend::detail
{
using geometry::TPinhole;

/** Pair i: point a[i] / pixel ua[i] in the reference view, b[i] / ub[i] in the
 *  other view; the motion T maps b-coordinates to a-coordinates. */
struct TCorrespondences
{
  std::vector<Eigen::Vector3d> a, b;
  std::vector<Eigen::Vector2d> ua, ub;
  /** Keypoint noise of pair i in pixels (coarse pyramid levels are less
   *  precise); empty = pixelSigma for all. */
  std::vector<double> sigma;
  std::size_t size() const { return a.size(); }
};

struct TRefineParams
{
  int iterations = 10;
  /** Inlier gate for a pair whose sigma is pixelSigma; each pair's gate is
   *  this times its own sigma / pixelSigma. */
  double inlierThresholdPx = 3.0;
  /** 3-D distance gate of the final inliers, metres. */
  double inlierThreshold3d = 0.06;
  /** Used for pairs without their own sigma. */
  double pixelSigma = 1.0;
  /** Huber threshold, in units of each pair's sigma. */
  double huber = 2.0;
  /** Axial depth noise (1 sigma, m) at depth z (m) for the estimator's
   *  information; empty = exact depth. */
  std::function<double(double)> depthSigma;
  /** 1-sigma (px, per image axis) of a shift common to all keypoints of
   *  one image, for the estimator's information: an error that does not
   *  average down with the keypoint count. 0 = none. */
  double commonPixelSigma = 0.0;
};

struct TRefineResult
{
  TRigid T;
  /** Information of the left-perturbation delta of T (see applyLeft). */
  Matrix6d information = Matrix6d::Zero();
  /** The estimator's information of the same delta, for the pose graph:
   *  each residual weighted by its covariance from the pixel noise of both
   *  keypoints (doubled: both directions use the same keypoints) and the
   *  depth noise of the point it reprojects, and scaled by the
   *  a-posteriori variance factor of the fit (the residuals' own spread). */
  Matrix6d edgeInformation = Matrix6d::Zero();
  std::vector<std::size_t> inliers;
  /** RMS reprojection error of the inliers, pixels, per axis (unweighted). */
  double rmsePx = 0;
  double rmse3d = 0;
};

/** Refines T0 on `initialInliers`, then re-selects the inliers among all
 *  pairs (both reprojection errors and the 3-D distance within the gates) and
 *  refines again while the set changes (at most 3 rounds). */
TRefineResult refineReprojection(
    const TPinhole& cam, const TCorrespondences& c, const TRigid& T0,
    const std::vector<std::size_t>& initialInliers, const TRefineParams& params);
}  // namespace roislam::frontend::detail
