/* Private: how far depth ICP can be trusted beside the features, measured
 * from their disagreement (refineWithDepth, icp_fusion = measured).
 *
 * Depth ICP's information is a model (CDepthIcp: the point-to-plane Hessian
 * of 25x fewer independent pairs than it uses, 3 mm floor). That model is
 * conservative on depth whose error is noise (a global-shutter camera,
 * synthetic depth: chi-square against ground truth below 6) and overconfident
 * on a camera whose depth is biased against its colour (the
 * fr1 Kinect: unsynchronised streams, rolling shutter, depth distortion):
 * there, ICP and the features disagree by 0.4-0.8 deg a frame where the
 * features' own uncertainty is 0.05 deg. Each frame that has both gives the
 * difference d of the two estimates and their covariances; if both were
 * honest, d' (Sf + Si)^-1 d would follow chi-square with 6 degrees of
 * freedom. The scale is the smallest k >= minScale for which the median of
 * d' (Sf + k Si)^-1 d over the recent frames is at most chi-square's median:
 * ICP's covariance scaled by k is what the data allow. The features'
 * covariance is taken as honest (their edges' chi-square against ground
 * truth, README "Honest edge information"). The front end's minScale is
 * CDepthIcp::kIndependentPairShare: ICP is trusted at most as if every pair
 * it used were independent, which on rendered depth it nearly is (median k
 * 0.04-0.08 on rendered loops, README "Keypoint noise per detector and
 * camera").
 *
 * ICP may also run on a share q of its pairs (every other cell of every
 * other row: q = 1/4), claiming Si / q. Its error is then modelled as a
 * part that fewer pairs do not change (the bias above: (k - 1) Si) plus
 * its noise, which grows as 1/q (Si / q, as claimed): the covariance of a
 * run on share q is (k - 1 + 1/q) Si, i.e. its own claim scaled by
 * kq = q (k - 1) + 1 (scaleFor). k is always that of all the pairs, so runs
 * on either share measure the same k. Below 1 there is no bias to speak of:
 * the error is noise alone, k Si for all the pairs and k Si / q for a share
 * q, whose claim Si / q is then scaled by k itself (kq = k). Both branches
 * meet at k = 1.
 *
 * Booking every disagreement against ICP is wrong where the features are
 * the worse of the two (a featureless room: 15 inliers on shading edges;
 * there the scale reads 6.2 where ICP is truly 7x better than its claim)
 * and hides how far the features' own claim is off. Both scales are
 * identifiable from the disagreements alone, because the two covariances
 * differ in shape from frame to frame (ICP is blind along a plane, the
 * features where they crowd): jointScales() fits d ~ N(0, a Sf + b Si) over
 * the window by maximum likelihood, robustly (Student-t with 4 degrees of
 * freedom: a few frames with a wrong feature match do not set it). Checked
 * against ground truth (README "Both estimators' scales from their
 * disagreement"): over whole runs on rgbd-simul renders the fit reads the
 * features' true scale within 10-18 % (0.16 for 0.14, 2.0 for 2.2, 0.80
 * for 0.91), where the one-scale model takes it as 1. On the fr1 Kinect the
 * fit reads 4.0 and 2.8 where the ground truth reads 6.8 and 5.6: part of
 * that is the ground truth's own noise, part error the two estimators
 * share, which their disagreement cannot see. Reported only (summary.json
 * tracking.feature_scale): fusing at the joint scales' ratio was measured
 * and lost (README).
 */
#pragma once

#include <roislam/frontend/TFrameResult.h>

#include <cstddef>
#include <deque>
#include <limits>
#include <optional>
#include <vector>

#include "RigidMath.h"

namespace roislam::frontend::detail
{
class CIcpConsistency
{
 public:
  /** window: the recent comparisons kept; minSamples: fewer -> no scale;
   *  minScale in (0, 1]: the least scale ICP's covariance may take (1: never
   *  trusted beyond its model). Throws std::invalid_argument. */
  explicit CIcpConsistency(
      std::size_t window = 30, std::size_t minSamples = 10, double minScale = 1.0);

  /** One frame's comparison: d = log(T_icp T_features^-1) in the left
   *  perturbation (fuseLeft's), with each estimate's covariance there, ICP
   *  having run on pairShare of its pairs (0 < pairShare <= 1). */
  void add(
      const Vector6d& d, const Matrix6d& featureCov, const Matrix6d& icpCov, double pairShare = 1);

  /** The scale k >= minScale of ICP's covariance, or nullopt before minSamples
   *  comparisons. +infinity when no scale up to kMaxScale explains the
   *  disagreement (ICP is then of no use beside the features). */
  std::optional<double> scale() const { return m_scale; }
  /** The scale of the claimed covariance of an ICP run on pairShare of its
   *  pairs: pairShare (k - 1) + 1 for k >= 1, k below (k = scale(); nullopt
   *  as scale()). */
  std::optional<double> scaleFor(double pairShare) const;
  /** The share of a full run's information that an ICP run on pairShare of
   *  its pairs keeps, under the model above: k / (k - 1 + 1 / pairShare) for
   *  k >= 1; pairShare itself (noise alone) below 1 and while no finite
   *  scale is known. */
  double informationKept(double pairShare) const;

  /** Both estimators' scales, fitted jointly (above): the features'
   *  covariance is truly about `features` times its claim, ICP's `icp`
   *  times (for all its pairs; scaleFor()'s model for a share). */
  struct TJointScales
  {
    double features = 1, icp = 1;
  };
  /** The joint fit over the window, or nullopt before a full window (two
   *  scales need more comparisons than one) or when the fit failed.
   *  Recomputed on every add() once the window is full. */
  std::optional<TJointScales> jointScales() const { return m_joint; }
  /** One comparison, as add() takes it. */
  struct TComparison
  {
    Vector6d d;
    Matrix6d featureCov, icpCov;
    double pairShare = 1;
  };
  /** The fit itself, over any comparisons (exposed for its tests), from a
   *  grid over e^-7..e^7 for each scale, or searched from `start` alone. */
  static std::optional<TJointScales> fitJointScales(
      const std::vector<TComparison>& samples,
      const std::optional<TJointScales>& start = std::nullopt);

  /** The median over the recent comparisons of ICP's information relative
   *  to the features', tr(Sf Si^-1) / 6 for all the pairs (a run on share
   *  q counts tr(Sf Si^-1) / 6 / q), at scale 1 (divide by the scale). */
  double medianShare() const { return m_share; }

  /** d' (Sf + k Si)^-1 d of one comparison (+infinity when singular). */
  static double chi2(
      const Vector6d& d, const Matrix6d& featureCov, const Matrix6d& icpCov, double k);

  std::size_t size() const { return m_samples.size(); }
  void reset();

  /** Chi-square's median with 6 degrees of freedom. */
  static constexpr double kChi2Median6 = 5.348120627;
  static constexpr double kMaxScale = 1e6;
  /** Chi-square's 0.99 quantile with 6 degrees of freedom. */
  static constexpr double kChi2Gate6 = 16.811893829;

 private:
  /** A comparison and its information share (medianShare()). */
  struct TSample : TComparison
  {
    double share = 0;
  };
  double medianChi2(double k) const;
  /** scaleFor()'s formula for a given k. */
  static double shareScale(double k, double pairShare);
  /** The scale and the median share of the samples held (after add()). */
  void update();

  std::size_t m_window, m_minSamples;
  double m_minScale;
  std::deque<TSample> m_samples;
  std::optional<double> m_scale;
  std::optional<TJointScales> m_joint;
  double m_share = 0;
};

/** Whether depth ICP's estimate (information icp, CPose3DPDFGaussianInf
 *  order), its covariance scaled by icpScale (CIcpConsistency::scale(): what
 *  its disagreement with the features measured; +infinity: of no use), has a
 *  smaller worst translation 1-sigma than another estimate of the same frame
 *  (information other; a singular one loses). The front end uses it where a
 *  frame's features failed and a chain through the previous frame competes
 *  with depth ICP (bridge_previous_frame). */
bool icpBetterDetermined(const TInformation66& icp, double icpScale, const TInformation66& other);
}  // namespace roislam::frontend::detail
