// Stage 3 of the front end: the motion predicted from the last one, then the
// frame's features registered against the recent keyframes (the ROI's first
// in ROI modes, the whole image's when those fail or leave the pose poorly
// determined).
#include <roislam/frontend/PoseUncertainty.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <tuple>

#include "OdometryWork.h"

namespace roislam::frontend
{
namespace
{
/** Overlap policy, or a full place (keyframe_place_limit): whether a
 *  registration against a keyframe may make it the reference. A keyframe
 *  without an ICP map (not a recent one: a revisited place) cannot have a
 *  poorly determined registration refined with depth (refineWithDepth), so
 *  it must not need that: at most icp_refine_sigma_m along its worst
 *  direction, and enough inliers not to make a keyframe. */
bool acceptsReference(
    bool revisit, bool hasIcpMap, const detail::TRegistration& r, const CRgbdOdometry::TOptions& o)
{
  if (!revisit || hasIcpMap)
    return true;
  if (static_cast<int>(r.inliers) < o.keyframe_min_inliers)
    return false;
  const auto s = worstSigmas(detail::toMrptEstimate(r).second);
  return s && !(o.icp_refine_sigma_m > 0 && s->translation_m > o.icp_refine_sigma_m);
}
}  // namespace

void CRgbdOdometry::registerWithRecent(const TKeyframe& query, TFrameWork& w) const
{
  // The overlap policy's candidates, then the last keyframe and the recent
  // older ones, until one registers (the last keyframe is always tried).
  const std::size_t nTry = 1 + static_cast<std::size_t>(m_options.recent_keyframes);
  std::vector<std::size_t> order = w.candidates;
  for (std::size_t k = 0; k <= w.lastKf && (k == 0 || order.size() < nTry); ++k)
    if (std::find(order.begin(), order.end(), w.lastKf - k) == order.end())
      order.push_back(w.lastKf - k);
  std::optional<std::tuple<detail::TRegistration, std::size_t, std::size_t>> fallback;
  // With followed features (roi_extraction = flow), the keyframe they were
  // followed from gets them as known pairs; others are matched with the
  // region's set, the head of w.cur (same indices).
  const bool followed = w.flowRef.has_value() && &query == &w.cur;
  for (std::size_t k = 0; k < order.size(); ++k)
  {
    const std::size_t id = order[k];
    std::size_t nm = 0;
    const bool known = followed && id == *w.flowRef;
    w.reg = m_impl->registerSets(
        known ? w.flowRefView : m_keyframes[id], followed && !known ? w.regionSet : query,
        m_options, &nm, &w.res.times, known ? &w.known : nullptr);
    if (k == 0 || w.reg)
      w.res.matches = nm;
    if (w.reg && k + 1 < order.size() &&
        !acceptsReference(
            usesOverlapPolicy() || w.placeFull, m_impl->icpMaps.count(id) > 0, *w.reg, m_options))
    {
      // Kept in case no later candidate registers.
      if (!fallback)
        fallback = {*w.reg, id, nm};
      w.reg.reset();
      continue;
    }
    if (w.reg)
    {
      w.ref = id;
      return;
    }
  }
  if (fallback)
    std::tie(w.reg, w.ref, w.res.matches) = *fallback;
}

void CRgbdOdometry::predictMotion(TFrameWork& w) const
{
  const TImpl& I = *m_impl;
  w.lastKf = m_keyframes.size() - 1;
  w.ref = w.lastKf;
  // Constant velocity, relative to the last keyframe.
  w.lastWorld = m_keyframes[w.lastKf].pose;
  if (I.haveLast)
    w.lastWorld = m_keyframes[I.lastRef].pose + I.lastRel;
  w.predictedWorld = w.lastWorld + I.velocity;
  w.predictedRel = w.predictedWorld - m_keyframes[w.lastKf].pose;
  const std::size_t nTry = 1 + static_cast<std::size_t>(m_options.recent_keyframes);
  if (!usesOverlapPolicy())
  {
    const auto limit = static_cast<std::size_t>(m_options.keyframe_place_limit);
    if (limit == 0)
      return;
    // A place that has its keyframes (a revisit): the nearest are the
    // candidates. Otherwise the last keyframe, unless the previous frame
    // still tracked an older one (it has just left a full place): the
    // keyframe this frame will make is then tied to that one.
    const auto place = detail::keyframesNear(
        m_keyframes, w.predictedWorld, m_options.keyframe_translation_m,
        m_options.keyframe_rotation_deg * M_PI / 180.0);
    if (place.size() >= limit)
    {
      w.placeFull = true;
      w.candidates.assign(place.begin(), place.begin() + std::min(nTry, place.size()));
    }
    else if (I.haveLast && I.lastRef != w.lastKf)
      w.candidates = {I.lastRef};
    if (!w.candidates.empty())
      w.ref = w.candidates.front();
    return;
  }
  // The reference: the newest keyframe whose view still overlaps the
  // predicted one enough (and within the motion bounds), else the one that
  // overlaps best, wherever it was made: a revisit tracks against the old
  // keyframes. 100 points per keyframe give the overlap to about 5 %.
  const detail::TReferenceGate gate{
      m_options.keyframe_min_overlap, m_options.keyframe_translation_m,
      m_options.keyframe_rotation_deg * M_PI / 180.0};
  w.candidates = detail::referenceCandidates(
      m_keyframes, w.predictedWorld, I.view(w.in.grey.size(), m_options), gate, nTry, 100);
  if (!w.candidates.empty())
    w.ref = w.candidates.front();
}

void CRgbdOdometry::followReference(TFrameWork& w, const cv::Rect& described) const
{
  const TImpl& I = *m_impl;
  const auto pyramid = I.flowPyramids.find(w.ref);
  if (pyramid == I.flowPyramids.end() || w.in.flowPyramid.empty())
    return;
  const auto t0 = detail::Clock::now();
  const TKeyframe& kf = m_keyframes[w.ref];
  w.flow = detail::followAnchors(
      kf, pyramid->second, w.in.flowPyramid, w.predictedWorld - kf.pose, I.K, I.dist,
      w.in.grey.size(), described, I.flowParams);
  // Lifted and corrected for the rolling shutter like the region's features.
  w.flowLifted = I.lift(w.flow.set, w.in.frame.depth, w.depthDt, w.rateApplied, m_options);
  w.regionSet = w.cur;
  w.flowRef = w.ref;
  w.flowRefView = detail::withAnchors(kf);
  rebuildFollowedSet(w);
  w.res.flowTracks = w.known.refIndex.size();
  w.res.trackingFeatures = w.cur.features.size();
  w.res.times.flow_ms += detail::msSince(t0);
}

void CRgbdOdometry::rebuildFollowedSet(TFrameWork& w) const
{
  const TKeyframe followed =
      detail::makeFeatureSet(w.flow.set, w.flowLifted, w.flowLifted.valid, m_impl->pinhole);
  w.cur = w.regionSet;
  w.cur.features = features::concat(w.regionSet.features, followed.features);
  w.cur.points.insert(w.cur.points.end(), followed.points.begin(), followed.points.end());
  w.cur.pixels.insert(w.cur.pixels.end(), followed.pixels.begin(), followed.pixels.end());
  w.known.first = w.regionSet.features.size();
  w.known.refIndex.clear();
  const int anchors0 = static_cast<int>(m_keyframes[*w.flowRef].points.size());
  for (int v : w.flowLifted.valid)
    w.known.refIndex.push_back(anchors0 + w.flow.anchorIndex[static_cast<std::size_t>(v)]);
}

void CRgbdOdometry::trackFeatures(TFrameWork& w)
{
  const TOptions& o = m_options;
  // Outside the ROI, unless its described features are too few to carry
  // the pose there (then everywhere).
  if (followsWithFlow() && w.regionOnly && !w.fallback)
    followReference(w, w.flowFallback ? cv::Rect() : w.res.work.region);
  registerWithRecent(w.cur, w);
  // A ROI registration on few inliers, or one that leaves the pose poorly
  // determined, is kept only when nothing better exists.
  const bool roiTracked = isRoiMode(o.mode) && !o.strict_roi && !w.fallback;
  bool weakRoi = w.reg && roiTracked && detail::isWeakRoiRegistration(*w.reg, o);
  // flow_describe_roi = when_weak: the anchors alone did not determine the
  // pose, so the ROI's features join them before the rest of the image is
  // described.
  if (roiTracked && (!w.reg || weakRoi) && describeRoi(w))
  {
    registerWithRecent(w.cur, w);
    weakRoi = w.reg && detail::isWeakRoiRegistration(*w.reg, o);
  }
  if (w.regionOnly)
  {
    // The region grows for the next frames while it does not determine the
    // pose, by half its area at a time, and shrinks back by a tenth per good
    // frame: a few weak frames in a row double it.
    double& g = m_impl->regionGrowth;
    g = (w.reg && !weakRoi) ? std::max(1.0, g * 0.9) : std::min(1e3, g * 1.5);
  }
  if ((w.reg && !weakRoi) || !roiTracked)
    return;
  // The ROI's features did not register (or barely): the whole image's may.
  extendToImage(w, weakRoi ? EExtension::RoiWeak : EExtension::RoiFailed);
  if (w.full.features.size() <= w.cur.features.size())
    return;
  const auto roiReg = w.reg;
  const std::size_t roiRef = w.ref;
  const std::size_t roiMatches = w.res.matches;
  registerWithRecent(w.full, w);
  // Kept when the whole image does not register, or registers but leaves
  // the pose even less determined (a blurred frame's few full-image
  // inliers can be worse than a sharp ROI's).
  if (!w.reg || (roiReg && detail::lessDetermined(*w.reg, *roiReg)))
  {
    w.reg = roiReg;
    w.ref = roiRef;
    w.res.matches = roiMatches;
    return;
  }
  w.fallback = true;
  w.flowRef.reset();
  w.cur = w.full;
  w.cur.fullImageFallback = true;
  w.res.trackingFeatures = w.cur.features.size();
}

void CRgbdOdometry::rescueWithAnchors(TFrameWork& w) const
{
  // An expected keyframe tracks with the whole image's features alone.
  // Where they fail or leave the pose undetermined (fast motion, blur: on
  // fr1/rpy such a frame fell to depth ICP, 4.6 deg off), the reference
  // keyframe's anchors, followed from where the predicted motion puts them,
  // join them; kept when that registration is the better determined.
  if (!followsWithFlow() || !w.keyframeExpected || w.flowRef ||
      (w.reg && !detail::isWeakRoiRegistration(*w.reg, m_options)))
    return;
  const auto before = w.reg;
  const std::size_t ref = w.ref, matches = w.res.matches;
  const TKeyframe tracked = w.cur;
  followReference(w, cv::Rect());
  if (!w.flowRef)
    return;
  registerWithRecent(w.cur, w);
  if (w.reg && (!before || !detail::lessDetermined(*w.reg, *before)))
  {
    w.anchorsJoinedFull = true;
    return;
  }
  w.reg = before;
  w.ref = ref;
  w.res.matches = matches;
  w.cur = tracked;
  w.flowRef.reset();
  w.res.flowTracks = 0;
  w.res.trackingFeatures = w.cur.features.size();
}
}  // namespace roislam::frontend
