/* How well a relative-pose measurement is determined, from its information
 * matrix: the 1-sigma along the worst-determined translation direction and
 * rotation axis. A registration from features crowded into a small image
 * region (a small ROI) can have many inliers and still leave a
 * rotation/translation ambiguity; these figures expose it (frames.csv, and
 * the ROI modes' max_roi_sigma_* fallback gate).
 */
#pragma once

#include <roislam/frontend/TFrameResult.h>

#include <optional>

namespace roislam::frontend
{
struct TPoseSigmas
{
  /** Square root of the largest eigenvalue of the (x, y, z) marginal
   *  covariance, metres. */
  double translation_m = 0;
  /** Same for the (yaw, pitch, roll) marginal, radians. */
  double rotation_rad = 0;
};

/** From an information matrix in CPose3DPDFGaussianInf order; nullopt when it
 *  is singular (not invertible) or not finite. */
std::optional<TPoseSigmas> worstSigmas(const TInformation66& information);
}  // namespace roislam::frontend
