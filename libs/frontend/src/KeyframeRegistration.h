/* Feature registration between two keyframe-like feature sets (a stored
 * keyframe and the current frame, or two keyframes): descriptor matching,
 * 3-D RANSAC on the lifted points, then Gauss-Newton refinement of the
 * reprojection error on the inliers, which also gives the information matrix.
 */
#pragma once

#include <roislam/frontend/CRgbdOdometry.h>
#include <roislam/frontend/TKeyframe.h>
#include <roislam/matching/CFeatureMatcher.h>
#include <roislam/matching/CRigidTransformRansac.h>

#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

#include "ReprojectionRefinement.h"
#include "RigidMath.h"

namespace roislam::frontend::detail
{
/** T maps points of the query set (cur) into the reference set's camera. */
struct TRegistration
{
  TRigid T;
  Matrix6d information;
  /** TRefineResult::edgeInformation: what the pose graph weighs it by. */
  Matrix6d edgeInformation = Matrix6d::Zero();
  std::size_t matches = 0, inliers = 0;
  double rmse3d = 0, rmsePx = 0;
  /** Every match as (reference feature, current feature) indices, and which
   *  of them are inliers: what refineRegistration() starts from. */
  std::vector<std::pair<int, int>> pairs;
  std::vector<std::size_t> inlierPairs;
};

/** A frame tracked by its described features against keyframe `ref` that
 *  did not become a keyframe: what the next frame may register against when
 *  that keyframe no longer registers (bridge_previous_frame). */
struct TTrackedFrame
{
  TKeyframe set;
  std::size_t ref = 0;
  /** set registered against keyframe ref. */
  TRegistration reg;
};

/** refToPrev chained with prevToCur: cur registered against ref, both
 *  informations composed (RigidMath.h composedInformation; the two taken as
 *  independent), the fewer inliers of the two. nullopt when a direction of
 *  either is undetermined. */
std::optional<TRegistration> chainRegistrations(
    const TRegistration& refToPrev, const TRegistration& prevToCur);

/** Correspondences known without matching (optical flow, FlowTracking.h):
 *  cur's features from `first` on, each with the ref feature it came from. */
struct TKnownPairs
{
  std::size_t first = 0;
  std::vector<int> refIndex;  //!< for cur feature first + j
  bool empty() const { return refIndex.empty(); }
};

/** Registers cur (query) against ref (train; its cached index is used when
 *  present). nullopt when fewer than o.min_inliers survive. The optional
 *  outputs receive the match count and add the matching / RANSAC times.
 *  With `known`, only cur's features before known->first are matched; the
 *  known pairs join the matches (RANSAC and refinement see both). */
std::optional<TRegistration> registerSets(
    const TKeyframe& ref, const TKeyframe& cur, const matching::CFeatureMatcher& matcher,
    const matching::CRigidTransformRansac& ransac, const TPinhole& cam,
    const CRgbdOdometry::TOptions& o, std::size_t* matchesOut, double* matchMs, double* ransacMs,
    const TKnownPairs* known = nullptr);

/** Refines r again on the same matches after cur's points and pixels were
 *  changed in place (the rolling-shutter correction with a better angular
 *  velocity), starting from r.T and its inliers. nullopt when fewer than
 *  o.min_inliers survive. */
std::optional<TRegistration> refineRegistration(
    const TKeyframe& ref, const TKeyframe& cur, const TRegistration& r, const TPinhole& cam,
    const CRgbdOdometry::TOptions& o);

/** 1 sigma per image axis, px, that an uncertainty of time_s seconds in
 *  when a keypoint was seen adds to it: the image speed of its optical-frame
 *  point X, the camera turning at `angular` (rad/s) and moving at `linear`
 *  (m/s), both in its own frame, times time_s. 0 for a point not in front
 *  of the camera. */
double motionSigmaPx(
    const mrpt::math::TPoint3D& X, const mrpt::math::TVector3D& angular,
    const mrpt::math::TVector3D& linear, const TPinhole& cam, double time_s);

/** A 6x6 Eigen matrix as MRPT's fixed-size one. */
TInformation66 toMrpt(const Matrix6d& m);

/** A registration (features or ICP; T maps the current frame into the
 *  reference) as an MRPT relative pose and its information in MRPT's
 *  (x, y, z, yaw, pitch, roll) order. */
template <class TResult>
std::pair<mrpt::poses::CPose3D, TInformation66> toMrptEstimate(const TResult& r)
{
  const mrpt::poses::CPose3D pose = toPose(r.T);
  return {pose, toMrpt(tangentInfoToYpr(r.information, pose))};
}

/** A registration's estimator information (features or ICP) in the
 *  parametrisation MRPT's SPA weighs edges by (SE(3) pseudo-log of the
 *  right perturbation, [x y z rx ry rz]). */
template <class TResult>
TInformation66 toSpaEstimate(const TResult& r)
{
  return toMrpt(tangentInfoToPseudoLog(r.edgeInformation, r.T));
}

/** A ROI registration to replace by a whole-image one when that registers:
 *  fewer inliers than min_roi_inliers, or its worst-determined direction
 *  beyond max_roi_sigma_m / max_roi_sigma_deg (PoseUncertainty.h). */
bool isWeakRoiRegistration(const TRegistration& r, const CRgbdOdometry::TOptions& o);

/** a's worst translation direction is less determined than b's. */
bool lessDetermined(const TRegistration& a, const TRegistration& b);
}  // namespace roislam::frontend::detail
