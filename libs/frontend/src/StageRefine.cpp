// Refinement of the front end's registration, and the frame's pose: the
// rolling-shutter correction with the velocity the registration measured,
// depth ICP for registrations that leave the pose poorly determined, and,
// when features failed, the depth-only and constant-velocity fallbacks.
#include <roislam/frontend/PoseUncertainty.h>

#include <algorithm>
#include <cmath>
#include <tuple>

#include "OdometryWork.h"

namespace roislam::frontend
{
using detail::Clock;
using detail::msSince;

namespace
{
/** Measured fusion runs ICP on a quarter of its pairs (every other cell of
 *  every other row, a quarter of the work) when, by the consistency's model
 *  (IcpConsistency.h: a bias fewer pairs do not change plus noise that
 *  grows as they fall), that keeps at least this share of its information:
 *  k >= 12. The fr1 Kinect reads k = 10-140 (its ICP error is bias), the
 *  synthetic loops 1 or below (noise: every pair counts). */
constexpr double kCoarseIcpMinInformationKept = 0.8;
/** The colour image's verdict between features and ICP: a sign test's z
 *  beyond 3 (one chance in 740 that a tie reads as ICP's win). */
constexpr double kColourVerdictZ = 3.0;
constexpr int kCoarseIcpStride = 2;

/** Whether depth ICP's estimate, its covariance scaled by icpScale, is
 *  better determined than reg's (icpBetterDetermined). */
bool losesToIcp(
    const detail::TRegistration& reg, const detail::CDepthIcp::TResult& icp, double icpScale)
{
  return detail::icpBetterDetermined(
      detail::toMrptEstimate(icp).second, icpScale, detail::toMrptEstimate(reg).second);
}

/** A frame bridged through the previous frame, with depth ICP available
 *  too: a chain is worth more than ICP where ICP disagrees with the
 *  features (fr1: its covariance scaled by 33-49), less where ICP agrees
 *  with them (rendered depth, global shutter: the chain claimed 4-12 mm
 *  where ICP had 1-1.5 mm, and kept it worse). So the better determined of
 *  the two, ICP's covariance scaled by what its disagreement with the
 *  features measured (before any measurement, the conservative model of
 *  ICP alone). */
bool chainLosesToIcp(
    const detail::TRegistration& chain, const detail::CDepthIcp::TResult& icp,
    const detail::CIcpConsistency& consistency)
{
  return losesToIcp(
      chain, icp, consistency.scale().value_or(detail::CDepthIcp::kUnverifiedCovarianceScale));
}

/** ICP's estimate in place of the features', its information divided by
 *  scale. */
void replaceWithIcp(
    detail::TRegistration& reg, TFrameResult& res, const detail::CDepthIcp::TResult& icp,
    double scale)
{
  reg.T = icp.T;
  reg.information = icp.information / scale;
  reg.edgeInformation = icp.edgeInformation / scale;
  res.icpRefined = true;
  res.icpReplacedFeatures = true;
  res.icpInformationShare = 1;
}
}  // namespace

void CRgbdOdometry::refineRollingShutter(TFrameWork& w)
{
  TImpl& I = *m_impl;
  const double readout = m_options.rolling_shutter_ms * 1e-3;
  const double stamp = w.in.frame.timestamp;
  if (!w.reg || readout == 0 || !I.haveStamp || !(stamp > I.lastStamp))
    return;
  // The velocity this registration measured since the last frame replaces
  // the predicted one (it lags by half a frame instead of one and a half),
  // and the same matches are refined again. Measured on fr1/rpy; a third
  // pass was not better.
  const mrpt::poses::CPose3D measured =
      (m_keyframes[w.ref].pose + detail::toPose(w.reg->T)) - w.lastWorld;
  const detail::TCameraRate rate = detail::cameraRate(measured, stamp - I.lastStamp);
  // The first keyframe, uncorrected so far, gets the velocity measured from
  // it to this frame (it was the last frame), and this registration is
  // refined against its corrected points.
  if (I.uncorrected && I.uncorrected->id == w.ref && I.lastStamp == m_keyframes[w.ref].timestamp)
    detail::correctKeyframe(m_keyframes[w.ref], *I.uncorrected, rate, readout, I.pinhole);
  I.uncorrected.reset();
  // Points and pixels only: the feature sets keep their descriptors.
  auto rebuild = [&]()
  {
    detail::updateFeatureSetPoints(w.full, w.lifted, w.lifted.valid, I.pinhole);
    if (w.flowRef)
    {
      detail::updateFeatureSetPoints(w.regionSet, w.lifted, w.chosen, I.pinhole);
      rebuildFollowedSet(w);
      return;
    }
    detail::updateFeatureSetPoints(
        w.cur, w.lifted, w.fallback ? w.lifted.valid : w.chosen, I.pinhole);
  };
  // Depth taken at another time than colour is read again with it too.
  auto correct = [&](const detail::TCameraRate& r)
  {
    detail::realignDepthTime(
        w.lifted, w.in.frame.depth, I.K, I.dist, I.pinhole, m_options, r, w.depthDt);
    detail::rectifyRollingShutter(w.lifted, r, readout, I.pinhole);
    if (!w.flowRef)
      return;
    detail::realignDepthTime(
        w.flowLifted, w.in.frame.depth, I.K, I.dist, I.pinhole, m_options, r, w.depthDt);
    detail::rectifyRollingShutter(w.flowLifted, r, readout, I.pinhole);
  };
  correct(rate);
  rebuild();
  if (auto again = detail::refineRegistration(
          w.reference(m_keyframes, w.ref), w.cur, *w.reg, I.pinhole, m_options))
  {
    w.reg = std::move(again);
    w.rateApplied = rate;
  }
  else
  {
    correct(w.ratePredicted);
    rebuild();
  }
}

void CRgbdOdometry::refineWithDepth(TFrameWork& w) const
{
  TImpl& I = *m_impl;
  if (!w.reg || !(m_options.icp_refine_sigma_m > 0) || !I.icpMaps.count(w.ref))
    return;
  // A feature registration that leaves the pose poorly determined (blur,
  // few inliers, features crowded in one region) is combined with depth ICP
  // against the same keyframe, started from it: the depth geometry
  // constrains exactly the directions the few features do not.
  const auto sg = worstSigmas(detail::toMrptEstimate(*w.reg).second);
  const bool weak = !sg || sg->translation_m > m_options.icp_refine_sigma_m;
  const bool measured = m_options.icp_fusion == "measured";
  ++I.framesSinceIcp;
  // A well-determined registration beside an ICP whose error is mostly
  // bias: a quarter of the pairs tells as much. A poorly determined one
  // gets every pair (ICP then carries the pose).
  const int stride =
      measured && !weak &&
              I.icpConsistency.informationKept(1.0 / (kCoarseIcpStride * kCoarseIcpStride)) >=
                  kCoarseIcpMinInformationKept
          ? kCoarseIcpStride
          : 1;
  const double pairShare = 1.0 / (stride * stride);
  if (!weak && !(measured && icpWorthRunning(pairShare)))
    return;
  const auto t0 = Clock::now();
  w.refineIcp = I.icp->align(I.icpMaps[w.ref], w.currentIcpMap(*I.icp), w.reg->T, stride);
  w.res.times.icp_ms += msSince(t0);
  I.framesSinceIcp = 0;
  if (!w.refineIcp)
    return;
  const auto& ir = w.refineIcp;
  w.res.icpPairShare = pairShare;
  const auto scale = measured ? measuredIcpScale(w, weak, pairShare) : 1.0;
  if (!scale)
    return;
  const detail::TFusedIcp fused{*ir, *scale};
  if (!detail::depthIcpJoins(*w.reg, fused, m_options))
  {
    // The two disagree beyond what the scale explains, and the colour image
    // did not side with ICP (or was not asked): one of them is wrong, and
    // the better determined of the two at the measured scale stands, as for
    // a chain through the previous frame (chainLosesToIcp). Keeping the
    // features here kept 15 inliers on shading edges 19 mm off where ICP
    // was right (rgbd-simul's bare featureless room, ROI SIFT, frame 166);
    // on the fr1 Kinect the scale (10-140) leaves ICP the worse determined.
    if (I.icpConsistency.scale() && losesToIcp(*w.reg, *ir, *scale))
      replaceWithIcp(*w.reg, w.res, *ir, *scale);
    return;
  }
  w.fusedIcp = fused;
  detail::fuseDepthIcp(*w.reg, fused);
  w.res.icpInformationShare = detail::depthIcpShare(*w.reg, fused);
  w.res.icpRefined = true;
}

std::optional<double> CRgbdOdometry::measuredIcpScale(
    TFrameWork& w, bool weak, double pairShare) const
{
  TImpl& I = *m_impl;
  const detail::CDepthIcp::TResult& ir = *w.refineIcp;
  // Measured fusion: every registration, ICP's information divided by the
  // scale its recent disagreement with the features asks for.
  const auto featureCov = detail::covarianceOf(w.reg->edgeInformation);
  const auto icpCov = detail::covarianceOf(ir.information);
  const detail::Vector6d d = detail::leftDifference(w.reg->T, ir.T);
  // Where the two disagree beyond their claims (ICP's covariance at its
  // least, every pair independent), one of them is wrong; their
  // covariances cannot tell which (IcpConsistency books it all against
  // ICP), the colour image can (PhotometricCheck.h). Where it sides with
  // ICP, ICP's estimate replaces the features', with its modelled
  // information, and the disagreement is not booked against ICP.
  if (m_options.icp_colour_check && featureCov && icpCov &&
      detail::CIcpConsistency::chi2(
          d, *featureCov, *icpCov, detail::CDepthIcp::kIndependentPairShare) >
          detail::CIcpConsistency::kChi2Gate6 &&
      colourSidesWithIcp(w, ir.T))
  {
    replaceWithIcp(*w.reg, w.res, ir, 1);
    w.res.icpOverruledFeatures = true;
    w.res.icpScale = I.icpConsistency.scale().value_or(0.0);
    return std::nullopt;
  }
  if (featureCov && icpCov)
    I.icpConsistency.add(d, *featureCov, *icpCov, pairShare);
  const auto k = I.icpConsistency.scaleFor(pairShare);
  w.res.icpScale = I.icpConsistency.scale().value_or(0.0);
  if (const auto joint = I.icpConsistency.jointScales())
  {
    w.res.featureScale = joint->features;
    w.res.icpJointScale = joint->icp;
  }
  const bool worth = icpWorthRunning(pairShare, true);
  // Until enough frames were compared: a poorly determined registration at
  // ICP's own claim (ICP carries the pose), a well-determined one at the
  // scale assumed for an unverified ICP. Not fusing the latter at all (as
  // before stop 52) left frames with 15-17 inliers on shading edges, 6-9 mm
  // 1-sigma, to make keyframes on their own for the first 80 frames of
  // rgbd-simul's bare featureless room (ROI SIFT: ATE 9.7 mm -> 3.1).
  if (!k)
    return weak ? 1.0 : detail::CDepthIcp::kUnverifiedCovarianceScale;
  // No scale explains the disagreement: ICP is of no use beside features.
  if (!std::isfinite(*k))
    return std::nullopt;
  // A poorly determined registration is always fused: its own covariance
  // is what cannot be trusted (a synthetic pan's turning point: 30
  // inliers, 5 cm off, ICP right). A well-determined one is not when ICP's
  // scaled share is below icp_min_share (the frame was a probe, it only
  // measured), nor when its own disagreement is beyond what the scale
  // explains (a fast turn, where depth and colour differ most:
  // depthIcpJoins).
  if (!weak && !worth)
    return std::nullopt;
  return *k;
}

bool CRgbdOdometry::colourSidesWithIcp(const TFrameWork& w, const geometry::TRigid& icpT) const
{
  TImpl& I = *m_impl;
  const auto it = I.photoKeyframes.find(w.ref);
  if (it == I.photoKeyframes.end())
    return false;
  // Sampled the first time a disagreement asks (most keyframes never do).
  auto& kf = it->second;
  if (!kf.samples)
    kf.samples = detail::photoSamples(kf.grey, kf.depth, I.K, I.dist, detail::depthRule(m_options));
  return detail::comparePhotometric(*kf.samples, w.in.grey, I.K, I.dist, w.reg->T, icpT).z() >
         kColourVerdictZ;
}

void detail::fuseDepthIcp(TRegistration& reg, const TFusedIcp& f)
{
  reg.T = detail::fuseLeft(reg.T, reg.information, f.icp.T, f.icp.information / f.scale);
  reg.information += f.icp.information / f.scale;
  reg.edgeInformation += f.icp.edgeInformation / f.scale;
}

double detail::depthIcpShare(const TRegistration& reg, const TFusedIcp& f)
{
  const Eigen::LDLT<Matrix6d> ldlt(reg.information);
  if (ldlt.info() != Eigen::Success || !(f.scale > 0))
    return 0;
  const double share = (f.icp.information / f.scale * ldlt.solve(Matrix6d::Identity())).trace() / 6;
  return std::isfinite(share) ? std::clamp(share, 0.0, 1.0) : 0.0;
}

bool detail::depthIcpJoins(
    const TRegistration& reg, const TFusedIcp& f, const CRgbdOdometry::TOptions& o)
{
  // A poorly determined registration always; a well-determined one under
  // measured fusion, as long as it agrees with ICP within what the scale
  // explains.
  const auto sg = worstSigmas(toMrptEstimate(reg).second);
  if (!sg || sg->translation_m > o.icp_refine_sigma_m)
    return true;
  if (o.icp_fusion != "measured")
    return false;
  const auto featureCov = covarianceOf(reg.edgeInformation);
  const auto icpCov = covarianceOf(f.icp.information);
  return !featureCov || !icpCov ||
         CIcpConsistency::chi2(leftDifference(reg.T, f.icp.T), *featureCov, *icpCov, f.scale) <=
             CIcpConsistency::kChi2Gate6;
}

bool CRgbdOdometry::icpWorthRunning(double pairShare, bool ignoreProbe) const
{
  // A depth ICP costs about as much as a frame's features (4 ms at 640 x
  // 480). Where its scaled information is a small share of the features'
  // (the fr1 Kinect: 1-10 %), fusing it changes little; it then runs only
  // as a probe, to keep the scale current: every icp_probe_interval
  // registrations, so that the window of comparisons spans a bounded stretch
  // of the run. On that Kinect the scale follows the motion (fr1/rpy: 63-196
  // from its first 10 comparisons, a median of 15-36 over the run, 3-7 at
  // its end). Before stop 54 the interval doubled after each probe that found
  // ICP not worth it, up to 8x: the window then spanned up to 2400 frames,
  // and the scale stayed where the run's first frames had set it
  // (traditional ORB on fr1/rpy: ICP fused into 8 of 250 frames, ATE 12.27
  // mm; at a constant interval 161 frames, 10.97 mm). The probes cost about
  // 0.03 ms a frame more than before (fr1/xyz, where ICP stays a probe).
  const TImpl& I = *m_impl;
  const auto k = I.icpConsistency.scale();
  if (!k)
    return true;
  if (std::isfinite(*k) &&
      I.icpConsistency.medianShare() / *k * I.icpConsistency.informationKept(pairShare) >=
          m_options.icp_min_share)
    return true;
  return !ignoreProbe &&
         I.framesSinceIcp >= static_cast<std::size_t>(std::max(m_options.icp_probe_interval, 1));
}

bool CRgbdOdometry::resolvePose(TFrameWork& w)
{
  TImpl& I = *m_impl;
  const TOptions& o = m_options;
  TFrameResult& res = w.res;
  // Features failed against every keyframe: through the previous frame
  // before depth ICP (on fr1 several times less accurate than features).
  if (!w.reg)
    bridgeFromPrevious(w);
  // Depth ICP against the last keyframe, where the features failed (for the
  // pose) or were bridged (to compare): once per frame.
  std::optional<detail::CDepthIcp::TResult> icp;
  if (o.icp_fallback && I.icpMaps.count(w.lastKf) > 0 && (!w.reg || w.bridged))
  {
    const auto t0 = Clock::now();
    icp = I.icp->align(
        I.icpMaps[w.lastKf], w.currentIcpMap(*I.icp), detail::fromPose(w.predictedRel));
    res.times.icp_ms += msSince(t0);
  }
  if (w.bridged && icp && chainLosesToIcp(*w.reg, *icp, I.icpConsistency))
  {
    w.reg.reset();
    w.bridged = false;
  }
  if (w.reg)
  {
    res.method = featureMethodOf(w);
    std::tie(res.relativePose, res.relativeInformation) = detail::toMrptEstimate(*w.reg);
    res.relativeEdgeInformation = detail::toSpaEstimate(*w.reg);
    res.inliers = w.reg->inliers;
  }
  else if (o.strict_roi && isRoiMode(o.mode))
  {
    res.method = ETrackingMethod::Lost;
    return false;
  }
  else
  {
    // Features failed: depth-only ICP against the last keyframe, else the
    // constant-velocity prediction (tracking never stops).
    w.ref = w.lastKf;
    res.method = ETrackingMethod::ConstantVelocity;
    res.relativePose = w.predictedRel;
    res.relativeInformation = scaledIdentity(o.constant_velocity_information_scale);
    res.relativeEdgeInformation = res.relativeInformation;
    res.inliers = 0;
    if (icp)
    {
      res.method = ETrackingMethod::DepthIcp;
      std::tie(res.relativePose, res.relativeInformation) = detail::toMrptEstimate(*icp);
      // Alone in the graph, unchecked by features: the conservative model.
      auto alone = *icp;
      alone.edgeInformation /= detail::CDepthIcp::kUnverifiedCovarianceScale;
      res.relativeEdgeInformation = detail::toSpaEstimate(alone);
      res.inliers = icp->pairs;
    }
  }
  res.referenceKeyframe = w.ref;
  res.pose = m_keyframes[w.ref].pose + res.relativePose;
  I.setVelocity(*res.pose - w.lastWorld, w.in.frame.timestamp);
  return true;
}
}  // namespace roislam::frontend
