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

#include "ReprojectionRefinement.h"
#include "RigidMath.h"

namespace roislam::frontend::detail
{
/** T maps points of the query set (cur) into the reference set's camera. */
struct TRegistration
{
  TRigid T;
  Matrix6d information;
  std::size_t matches = 0, inliers = 0;
  double rmse3d = 0, rmsePx = 0;
};

/** Registers cur (query) against ref (train; its cached index is used when
 *  present). nullopt when fewer than o.min_inliers survive. The optional
 *  outputs receive the match count and add the matching / RANSAC times. */
std::optional<TRegistration> registerSets(
    const TKeyframe& ref, const TKeyframe& cur, const matching::CFeatureMatcher& matcher,
    const matching::CRigidTransformRansac& ransac, const TPinhole& cam,
    const CRgbdOdometry::TOptions& o, std::size_t* matchesOut, double* matchMs, double* ransacMs);
}  // namespace roislam::frontend::detail
