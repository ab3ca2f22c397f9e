// The keyframe stages of the front end: the first keyframe (the map's
// origin), the keyframe decision, a new keyframe's constraints to the recent
// keyframes, and its storage.
#include <roislam/common/Median.h>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>
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
  kf.regionDepth = common::upperMedian(std::move(z));
}
}  // namespace

void CRgbdOdometry::setAnchors(TKeyframe& kf, TFrameWork& w) const
{
  const TImpl& I = *m_impl;
  const auto t0 = Clock::now();
  kf.anchorKeypoints.clear();
  kf.anchorPoints.clear();
  kf.anchorPixels.clear();
  if (m_options.flow_anchors == "features")
  {
    // The keyframe's own features with depth, lifted and corrected as they
    // are: no detection of their own (README "Anchors from the keyframe's
    // features").
    for (int i : detail::spacedStrongest(kf.features.keypoints, w.in.grey.size(), I.flowParams))
    {
      const auto u = static_cast<std::size_t>(i);
      kf.anchorKeypoints.push_back(kf.features.keypoints[u].pt);
      kf.anchorPoints.push_back(kf.points[u]);
      kf.anchorPixels.push_back(kf.pixels[u]);
    }
    w.res.times.flow_ms += msSince(t0);
    return;
  }
  const features::TFeatureSet corners = detail::anchorCandidates(w.in.grey, I.flowParams);
  // The keyframe's depth rule, depth-time and rolling-shutter corrections,
  // as its features'.
  const detail::TLiftedFeatures lifted =
      I.lift(corners, w.in.frame.depth, w.depthDt, w.rateApplied, m_options);
  for (int i : lifted.valid)
  {
    const auto u = static_cast<std::size_t>(i);
    const Eigen::Vector3d X = I.pinhole.backProject(lifted.undistorted[u], lifted.z[u]);
    kf.anchorKeypoints.push_back(corners.keypoints[u].pt);
    kf.anchorPoints.emplace_back(X.x(), X.y(), X.z());
    kf.anchorPixels.push_back(lifted.undistorted[u]);
  }
  w.res.times.flow_ms += msSince(t0);
}

void CRgbdOdometry::startMap(TFrameWork& w)
{
  if (w.strictLost)
  {
    // strict_roi: the dissertation's version has no trajectory without a ROI.
    w.res.method = ETrackingMethod::Lost;
    return;
  }
  // The map's first keyframe stores the whole image too (the first frame
  // of a ROI mode described its region only).
  if (m_options.keyframe_full_features)
    extendToImage(w, EExtension::Keyframe);
  w.res.method = ETrackingMethod::Initial;
  w.res.pose = m_initialPose;
  w.res.relativeInformation = scaledIdentity(1e6);
  w.res.relativeEdgeInformation = w.res.relativeInformation;
  insertKeyframe(w, m_initialPose);
}

bool CRgbdOdometry::needsKeyframe(const TFrameWork& w) const
{
  const TOptions& o = m_options;
  // A bridged frame no longer registers against any keyframe: the next
  // frames need it as one. Inliers below keyframe_min_inliers are news only
  // where this keyframe could give that many: where a registration against
  // it (or it is the map's first) reached the floor, by described features
  // or by its anchors alike. In a room whose only features lie on shading
  // edges (15-37 SIFT inliers, about 15 anchors) every frame would
  // otherwise become a keyframe, and the chain of 200-300 edges drifted
  // where the motion policy's 22 did not (README "Keyframes where the
  // features never were"). Counting a keyframe's anchors instead (20-30
  // there, of which flow keeps 18-25 inliers) made a keyframe of every
  // other frame for its first 60 (README "Flow at the inlier floor").
  const bool reachedFloor = m_impl->atInlierFloor.count(w.ref) > 0;
  bool fewInliers = w.bridged || (isFeatureMethod(w.res.method) && reachedFloor &&
                                  static_cast<int>(w.res.inliers) < o.keyframe_min_inliers);
  // Fewer than a share of the most this keyframe gave: the registrations
  // against it are wearing out (counts differ by detector and scene, the
  // share does not).
  const auto best = m_impl->bestInliers.find(w.ref);
  if (o.keyframe_min_inlier_share > 0 && isFeatureMethod(w.res.method) &&
      best != m_impl->bestInliers.end() &&
      static_cast<double>(w.res.inliers) <
          o.keyframe_min_inlier_share * static_cast<double>(best->second))
    fewInliers = true;
  // ROI modes: the ROI's registration was weak or failed, so the frame was
  // described on the whole image (trackFeatures) and registered. The
  // keyframe's view is wearing out, and making the frame a keyframe costs
  // no second description. (On fr1/rpy the frames before a blurred one end
  // so: made keyframes, the blurred one registers against a sharp, near
  // neighbour instead of falling to depth ICP.) Not where depth ICP
  // carries the registration (more than half its information, or the
  // colour sided with it): depth does not blur, and the ROI then fails for
  // want of texture, not of view (a featureless room: every frame). Nor
  // where the keyframe found no ROI: a region it never had cannot wear out
  // (the same room, ROI SIFT: fallbacks of 15-17 inliers on shading edges
  // made 19 of its 36 keyframes, the worst of them 3-8 mm off).
  const bool icpCarries = w.res.icpInformationShare > 0.5;
  const bool hadRoi = m_keyframes[w.ref].roi.has_value();
  const EExtension ext = w.res.work.extension;
  if (o.keyframe_on_weak_roi && isFeatureMethod(w.res.method) && !icpCarries && hadRoi &&
      (ext == EExtension::RoiWeak || ext == EExtension::RoiFailed))
    fewInliers = true;
  // Anchors alone: their pairs are known, so their share of inliers says
  // how much of the keyframe's view still moves as one with the frame.
  if (o.keyframe_min_flow_inlier_share > 0 && w.res.method == ETrackingMethod::Flow &&
      w.res.matches > 0 &&
      static_cast<double>(w.res.inliers) <
          o.keyframe_min_flow_inlier_share * static_cast<double>(w.res.matches))
    fewInliers = true;
  return keyframeCriteria(w, *w.res.pose, fewInliers);
}

bool CRgbdOdometry::expectsKeyframe(const TFrameWork& w) const
{
  // Only where a keyframe costs an extension at full resolution: the
  // region (or ROI) first, then the rest of the image band by band, each
  // band its own detection pass, and a second registration with the whole
  // image's features. With roi_extension_scale < 1 the bands are cheaper
  // than one whole-image pass. Without a velocity the prediction is the
  // last pose: nothing expected.
  const TOptions& o = m_options;
  return o.keyframe_prediction && describesRegions() && o.keyframe_full_features &&
         o.keyframe_full_registration && o.roi_extension_scale >= 1 && m_impl->velocityDt > 0 &&
         keyframeCriteria(w, w.predictedWorld, false);
}

bool CRgbdOdometry::keyframeCriteria(
    const TFrameWork& w, const mrpt::poses::CPose3D& pose, bool fewInliers) const
{
  const TOptions& o = m_options;
  const bool overlap = usesOverlapPolicy();
  // Motion policy: on the motion since the last keyframe, the inliers left,
  // and whether the last keyframe still registered. Overlap policy: on what
  // the frame still sees of its reference keyframe (wherever that was made),
  // the inliers, and the motion since the reference as optional bounds.
  // A full place (keyframe_place_limit): on the motion since the reference,
  // one of the place's keyframes, wherever it was made.
  const TKeyframe& from = m_keyframes[overlap || w.placeFull ? w.ref : w.lastKf];
  const mrpt::poses::CPose3D since = pose - from.pose;
  const double dist = since.translation().norm();
  const double angDeg = detail::rotationAngle(since) * 180.0 / M_PI;
  if (!overlap)
    return dist > o.keyframe_translation_m || angDeg > o.keyframe_rotation_deg ||
           (w.ref != w.lastKf && !w.placeFull) || fewInliers;
  if ((o.keyframe_translation_m > 0 && dist > o.keyframe_translation_m) ||
      (o.keyframe_rotation_deg > 0 && angDeg > o.keyframe_rotation_deg) || fewInliers)
    return true;
  return detail::viewOverlap(from, since, m_impl->view(w.in.grey.size(), o)) <
         o.keyframe_min_overlap;
}

void CRgbdOdometry::makeKeyframeConstraints(TFrameWork& w)
{
  TImpl& I = *m_impl;
  const TOptions& o = m_options;
  TFrameResult& res = w.res;
  const auto t0 = Clock::now();
  // ROI modes: the keyframe's edges come from the whole image's features it
  // stores anyway (as loop closures do); the ROI tracks the frames between.
  // Depth ICP joined the frame's own registration (refineWithDepth): it
  // joins this one by the same rule. Dropping it cost the ICL-like loop
  // most: a flow frame made keyframe 237 on the features alone (3.5 mm
  // 1-sigma instead of 0.2) and the frames after it drifted 2.5 mm.
  const bool fullEdges = isRoiMode(o.mode) && !o.strict_roi && o.keyframe_full_features &&
                         o.keyframe_full_registration &&
                         ((w.flowRef.has_value() && !w.anchorsJoinedFull) ||
                          w.cur.features.size() < w.full.features.size());
  // Not where depth ICP's estimate replaced the frame's features
  // (StageRefine.cpp): the whole image's features see the same scene.
  if (fullEdges && isFeatureMethod(res.method) && !res.icpReplacedFeatures)
    if (auto r = I.registerSets(m_keyframes[w.ref], w.full, o))
    {
      if (w.fusedIcp && detail::depthIcpJoins(*r, *w.fusedIcp, o))
        detail::fuseDepthIcp(*r, *w.fusedIcp);
      std::tie(res.relativePose, res.relativeInformation) = detail::toMrptEstimate(*r);
      res.relativeEdgeInformation = detail::toSpaEstimate(*r);
      res.inliers = r->inliers;
      res.pose = m_keyframes[w.ref].pose + res.relativePose;
      I.setVelocity(*res.pose - w.lastWorld, w.in.frame.timestamp);
    }
  // Followed anchors carry no descriptors: other keyframes are matched with
  // the frame's described features only.
  const TKeyframe& edgeSet = fullEdges || w.flowRef ? w.full : w.cur;
  TKeyframeConstraint first;
  first.fromKeyframe = w.ref;
  first.toKeyframe = m_keyframes.size();
  first.relativePose = res.relativePose;
  first.information = res.relativeInformation;
  first.edgeInformation = res.relativeEdgeInformation;
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
    auto r = I.registerSets(m_keyframes[id], edgeSet, o);
    if (!r && I.previous && I.previous->ref == id)
    {
      // The keyframe the previous frame tracked, chained through it.
      r = I.chainedThroughPrevious(edgeSet, o);
      res.bridgedConstraints += r ? 1 : 0;
    }
    if (!r)
      continue;
    TKeyframeConstraint c;
    c.fromKeyframe = id;
    c.toKeyframe = first.toKeyframe;
    std::tie(c.relativePose, c.information) = detail::toMrptEstimate(*r);
    c.edgeInformation = detail::toSpaEstimate(*r);
    c.method = featureMethodOf(w);
    c.inliers = r->inliers;
    res.constraints.push_back(c);
  }
  res.times.keyframe_ms = msSince(t0);
}

cv::Rect CRgbdOdometry::keyframeRegion(const TFrameWork& w) const
{
  const TOptions& o = m_options;
  const TFrameResult& res = w.res;
  // The next frames follow the region this keyframe described densely while
  // it tracked well; after a failure or a weak registration, a new one from
  // stage 1 (the frame's ROI grown as in StageExtract.cpp).
  const bool regionTracked = res.work.extension == EExtension::None ||
                             res.work.extension == EExtension::Keyframe ||
                             res.work.extension == EExtension::ExpectedKeyframe;
  // Flow mode: the next frames follow its stage-1 ROI itself.
  if (res.roi && followsWithFlow())
    return *res.roi & cv::Rect(cv::Point(0, 0), w.in.grey.size());
  if (res.roi && !regionTracked)
    return detail::trackingRegion(
        *res.roi, w.in.grey.size(), o.roi_min_area_fraction, o.roi_min_aspect);
  return res.work.region;
}

void CRgbdOdometry::trimRecentKeyframeStores()
{
  // Search indexes, ICP maps, photometric samples, flow pyramids and
  // inlier bookkeeping only for the keyframes every frame is matched
  // against (memory).
  TImpl& I = *m_impl;
  const std::size_t keep = static_cast<std::size_t>(m_options.recent_keyframes) + 1;
  if (m_keyframes.size() > keep)
    m_keyframes[m_keyframes.size() - 1 - keep].index.reset();
  auto trim = [keep](auto& byKeyframe)
  {
    while (byKeyframe.size() > keep)
      byKeyframe.erase(byKeyframe.begin());
  };
  trim(I.icpMaps);
  trim(I.photoKeyframes);
  trim(I.bestInliers);
  trim(I.atInlierFloor);
  trim(I.flowPyramids);
}

void CRgbdOdometry::insertKeyframe(TFrameWork& w, const mrpt::poses::CPose3D& pose)
{
  TImpl& I = *m_impl;
  const TOptions& o = m_options;
  TFrameResult& res = w.res;
  // Traditional mode, and flow frames that followed their reference's ROI:
  // stage 1 for keyframes, whose ROI the back end uses as a landmark (and
  // the next flow frames follow).
  detectRoi(w);
  const auto t0 = Clock::now();
  const double timedBefore = res.times.icp_ms + res.times.flow_ms;
  // Stored for later matching: the whole image's features (unless
  // keyframe_full_features is off), so that the next frames' ROI, which
  // moves and changes size, still finds its partners.
  TKeyframe& kf = o.keyframe_full_features ? w.full : w.cur;
  kf.fullImageFallback = w.fallback;
  kf.roi = res.roi;
  setRegion(kf, keyframeRegion(w));
  kf.id = m_keyframes.size();
  kf.pose = pose;
  m_keyframes.push_back(std::move(kf));
  ++m_stats.keyframes;
  res.isNewKeyframe = true;
  res.newKeyframeId = m_keyframes.back().id;
  // The frame's map, if depth refinement built it already.
  const auto tMap = Clock::now();
  w.currentIcpMap(*I.icp);
  I.icpMaps[res.newKeyframeId] = std::move(*w.icpMap);
  w.icpMap.reset();
  // Copies: a frame source may decode the next frames into the same buffers.
  if (o.icp_fusion == "measured" && o.icp_refine_sigma_m > 0 && o.icp_colour_check)
    I.photoKeyframes[res.newKeyframeId] = {w.in.grey.clone(), w.in.frame.depth.clone(), {}};
  res.times.icp_ms += msSince(tMap);
  // Rolling shutter: a keyframe made before any velocity is known is
  // corrected once the next frame has measured one (StageRefine.cpp).
  I.uncorrected.reset();
  if (o.rolling_shutter_ms != 0 && !(I.velocityDt > 0))
    I.uncorrected = detail::uncorrectedKeyframe(
        res.newKeyframeId, w.lifted,
        o.keyframe_full_features || w.fallback ? w.lifted.valid : w.chosen);
  m_keyframes.back().index =
      std::make_shared<matching::CFeatureIndex>(o.matcher, m_keyframes.back().features);
  // The map's first keyframe has no registration to tell: its frames' count
  // below the floor is news, as before any keyframe.
  if (res.method == ETrackingMethod::Initial)
    I.atInlierFloor.insert(res.newKeyframeId);
  if (followsWithFlow())
  {
    setAnchors(m_keyframes.back(), w);
    // Followed from by the next frames: with its derivatives (FlowTracking.h).
    const auto tPyramid = Clock::now();
    I.flowPyramids[res.newKeyframeId] =
        detail::flowPyramidOf(w.in.grey, w.featureImage, I.flowParams, true);
    res.times.flow_ms += msSince(tPyramid);
  }
  trimRecentKeyframeStores();
  I.haveLast = true;
  I.lastRef = res.newKeyframeId;
  I.lastRel = mrpt::poses::CPose3D();
  // The rest of the storage (stage 1 excepted, its own column): the search
  // index and the bookkeeping. Each part is counted in one column only.
  res.times.keyframe_ms += msSince(t0) - (res.times.icp_ms + res.times.flow_ms - timedBefore);
}
}  // namespace roislam::frontend
