// The keyframe stages of the front end: the first keyframe (the map's
// origin), the keyframe decision, a new keyframe's constraints to the recent
// keyframes, and its storage.
#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

#include "OdometryWork.h"
#include "TrackingRegion.h"

namespace roislam::frontend
{
using detail::Clock;
using detail::msSince;

namespace
{
/** The tracking region the next frames follow, with the median depth of the
 *  keyframe's features inside it (the depth its corners are moved at). */
void setRegion(TKeyframe& kf, const cv::Rect& region)
{
  kf.region = region;
  kf.regionDepth = 0;
  std::vector<double> z;
  const cv::Rect2f box(region);
  for (std::size_t i = 0; i < kf.points.size(); ++i)
    if (box.contains(kf.features.keypoints[i].pt))
      z.push_back(kf.points[i].z);
  if (z.empty())
    return;
  std::nth_element(z.begin(), z.begin() + static_cast<std::ptrdiff_t>(z.size() / 2), z.end());
  kf.regionDepth = z[z.size() / 2];
}
}  // namespace

void CRgbdOdometry::startMap(TFrameWork& w)
{
  if (w.strictLost)
  {
    // strict_roi: the dissertation's version has no trajectory without a ROI.
    w.res.method = ETrackingMethod::Lost;
    return;
  }
  w.res.method = ETrackingMethod::Initial;
  w.res.pose = m_initialPose;
  w.res.relativeInformation = scaledIdentity(1e6);
  insertKeyframe(w, m_initialPose);
}

bool CRgbdOdometry::needsKeyframe(const TFrameWork& w) const
{
  const TOptions& o = m_options;
  // On the motion since the last keyframe, the inliers left, and whether the
  // last keyframe still registered.
  const mrpt::poses::CPose3D sinceLast = *w.res.pose - m_keyframes[w.lastKf].pose;
  const double dist = sinceLast.translation().norm();
  const double angDeg = detail::rotationAngle(sinceLast) * 180.0 / M_PI;
  if (dist > o.keyframe_translation_m || angDeg > o.keyframe_rotation_deg || w.ref != w.lastKf)
    return true;
  return isFeatureMethod(w.res.method) && static_cast<int>(w.res.inliers) < o.keyframe_min_inliers;
}

void CRgbdOdometry::makeKeyframeConstraints(TFrameWork& w)
{
  TImpl& I = *m_impl;
  const TOptions& o = m_options;
  TFrameResult& res = w.res;
  const auto t0 = Clock::now();
  // ROI modes: the keyframe's edges come from the whole image's features it
  // stores anyway (as loop closures do); the ROI tracks the frames between.
  const bool fullEdges = isRoiMode(o.mode) && !o.strict_roi && o.keyframe_full_features &&
                         o.keyframe_full_registration &&
                         w.cur.features.size() < w.full.features.size();
  if (fullEdges && isFeatureMethod(res.method))
    if (const auto r = I.registerSets(m_keyframes[w.ref], w.full, o))
    {
      std::tie(res.relativePose, res.relativeInformation) = detail::toMrptEstimate(*r);
      res.inliers = r->inliers;
      res.pose = m_keyframes[w.ref].pose + res.relativePose;
      I.setVelocity(*res.pose - w.lastWorld, w.in.frame.timestamp);
    }
  const TKeyframe& edgeSet = fullEdges ? w.full : w.cur;
  TKeyframeConstraint first;
  first.fromKeyframe = w.ref;
  first.toKeyframe = m_keyframes.size();
  first.relativePose = res.relativePose;
  first.information = res.relativeInformation;
  first.method = res.method;
  first.inliers = res.inliers;
  res.constraints.push_back(first);
  int extra = 0;
  for (std::size_t k = 0; k <= w.lastKf && extra < o.recent_keyframes; ++k)
  {
    const std::size_t id = w.lastKf - k;
    if (id == w.ref)
      continue;
    ++extra;
    const auto r = I.registerSets(m_keyframes[id], edgeSet, o);
    if (!r)
      continue;
    TKeyframeConstraint c;
    c.fromKeyframe = id;
    c.toKeyframe = first.toKeyframe;
    std::tie(c.relativePose, c.information) = detail::toMrptEstimate(*r);
    c.method = featureMethod(o.mode, w.fallback);
    c.inliers = r->inliers;
    res.constraints.push_back(c);
  }
  res.times.keyframe_ms = msSince(t0);
}

void CRgbdOdometry::insertKeyframe(TFrameWork& w, const mrpt::poses::CPose3D& pose)
{
  TImpl& I = *m_impl;
  const TOptions& o = m_options;
  TFrameResult& res = w.res;
  if (!w.in.roiDetected)
  {
    // Traditional mode: stage 1 for keyframes only, whose ROI the back end
    // uses as a landmark.
    const auto t0 = Clock::now();
    if (const auto r = I.roiDetector.detect(w.in.grey, w.in.frame.rgb))
      res.roi = r->box;
    res.times.roi_ms += msSince(t0);
  }
  const auto t0 = Clock::now();
  // Stored for later matching: the whole image's features (unless
  // keyframe_full_features is off), so that the next frames' ROI, which
  // moves and changes size, still finds its partners.
  TKeyframe& kf = o.keyframe_full_features ? w.full : w.cur;
  kf.fullImageFallback = w.fallback;
  kf.roi = res.roi;
  // The next frames follow the region this keyframe described densely while
  // it tracked well; after a failure or a weak registration, a new one from
  // stage 1 (the frame's ROI grown as in StageExtract.cpp).
  const bool regionTracked =
      res.work.extension == EExtension::None || res.work.extension == EExtension::Keyframe;
  setRegion(
      kf, regionTracked || !res.roi
              ? res.work.region
              : detail::trackingRegion(
                    *res.roi, w.in.grey.size(), o.roi_min_area_fraction, o.roi_min_aspect));
  kf.id = m_keyframes.size();
  kf.pose = pose;
  m_keyframes.push_back(std::move(kf));
  ++m_stats.keyframes;
  res.isNewKeyframe = true;
  res.newKeyframeId = m_keyframes.back().id;
  I.icpMaps[res.newKeyframeId] = I.icp->buildMap(w.in.frame.depth);
  // Rolling shutter: a keyframe made before any velocity is known is
  // corrected once the next frame has measured one (StageRefine.cpp).
  I.uncorrected.reset();
  if (o.rolling_shutter_ms != 0 && !(I.velocityDt > 0))
    I.uncorrected = detail::uncorrectedKeyframe(
        res.newKeyframeId, w.lifted,
        o.keyframe_full_features || w.fallback ? w.lifted.valid : w.chosen);
  // Search indexes and ICP maps only for the keyframes every frame is
  // matched against (memory).
  const std::size_t keep = static_cast<std::size_t>(o.recent_keyframes) + 1;
  m_keyframes.back().index =
      std::make_shared<matching::CFeatureIndex>(o.matcher, m_keyframes.back().features);
  if (m_keyframes.size() > keep)
    m_keyframes[m_keyframes.size() - 1 - keep].index.reset();
  while (I.icpMaps.size() > keep)
    I.icpMaps.erase(I.icpMaps.begin());
  I.haveLast = true;
  I.lastRef = res.newKeyframeId;
  I.lastRel = mrpt::poses::CPose3D();
  res.times.icp_ms += msSince(t0);
}
}  // namespace roislam::frontend
