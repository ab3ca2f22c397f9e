// Stage 2 and lifting of the front end. ROI modes describe features in the
// tracking region (the ROI grown to track with) and extend to the rest of
// the image only when the frame needs it; traditional mode (and strict_roi,
// roi_extraction = image) describes the whole image once, the ROI selecting
// its subset. Keypoints are lifted to 3-D with the registered depth and
// corrected for the rolling shutter with the last motion's velocity.
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <set>
#include <tuple>

#include "OdometryWork.h"
#include "TrackingRegion.h"

namespace roislam::frontend
{
using detail::Clock;
using detail::msSince;

namespace
{
/** The image outside `region`, band by band (detail::outside), with the
 *  cap's share of each band's area, at `scale` of the working image's
 *  resolution: the region's pixels are never described again. Keypoints
 *  come back in the camera's pixels (sizes too); `pixels` counts the pixels
 *  the detector ran on, at its resolution (the work). */
features::TFeatureSet describeOutside(
    const features::CFeatureExtractor& extractor, const detail::TWorkingImage& work,
    const cv::Rect& region, int cap, double extensionScale, std::size_t* pixels)
{
  const cv::Size image = work.image;
  cv::Mat img = work.grey;
  if (extensionScale < 1)
    cv::resize(work.grey, img, cv::Size(), extensionScale, extensionScale, cv::INTER_AREA);
  // The detector's image relative to the camera's.
  const double scale = extensionScale / static_cast<double>(1 << work.shift);
  features::TFeatureSet ext;
  *pixels = 0;
  for (const cv::Rect& band : detail::outside(region, image))
  {
    const int bandCap =
        cap > 0 ? std::max(
                      1, static_cast<int>(
                             std::ceil(cap * static_cast<double>(band.area()) / image.area())))
                : 0;
    // The band in the scaled image, rounded outwards (keypoints that land in
    // the region once scaled back are dropped below).
    std::size_t px = 0;
    ext = features::concat(
        ext, extractor.extractIn(img, detail::scaledOutwards(band, scale), bandCap, &px));
    *pixels += px;
  }
  if (scale >= 1)
    return ext;
  std::vector<int> keep;
  const cv::Rect2f inRegion(region);
  // The bands, rounded outwards at the lower resolution, may share a row or
  // column there: a keypoint found in both is kept once.
  std::set<std::tuple<float, float, int>> seen;
  for (std::size_t i = 0; i < ext.size(); ++i)
  {
    cv::KeyPoint& k = ext.keypoints[i];
    // Pixel centres: (u + 0.5) / scale - 0.5.
    k.pt.x = static_cast<float>((k.pt.x + 0.5) / scale - 0.5);
    k.pt.y = static_cast<float>((k.pt.y + 0.5) / scale - 0.5);
    k.size = static_cast<float>(k.size / scale);
    if (!inRegion.contains(k.pt) && seen.insert({k.pt.x, k.pt.y, k.octave}).second)
      keep.push_back(static_cast<int>(i));
  }
  return ext.select(keep);
}

/** The indices `idx` of set's features whose keypoint lies inside `box`. */
std::vector<int> inside(
    const features::TFeatureSet& set, const std::vector<int>& idx, const cv::Rect& box)
{
  const cv::Rect2f b(box);
  std::vector<int> in;
  for (int i : idx)
    if (b.contains(set.keypoints[static_cast<std::size_t>(i)].pt))
      in.push_back(i);
  return in;
}

/** A flow frame's cap for its ROI: the image's feature density (the ROI's
 *  share of max_features, 0 = no cap), at least min_roi_features. */
int roiFeatureCap(const CRgbdOdometry::TOptions& o, const cv::Rect& roi, const cv::Size& image)
{
  const int cap = o.extractor.max_features;
  if (cap <= 0 || roi.empty())
    return cap;
  return std::max(
      o.min_roi_features,
      static_cast<int>(std::ceil(cap * static_cast<double>(roi.area()) / image.area())));
}
}  // namespace

bool CRgbdOdometry::describesRegions() const
{
  return isRoiMode(m_options.mode) && !m_options.strict_roi &&
         (m_options.roi_extraction == "region" || m_options.roi_extraction == "flow");
}

bool CRgbdOdometry::followsWithFlow() const
{
  return describesRegions() && m_options.roi_extraction == "flow";
}

void CRgbdOdometry::detectRoi(TFrameWork& w) const
{
  if (w.roiDetected)
    return;
  const auto t0 = Clock::now();
  if (const auto r = m_impl->roiDetector.detect(w.in.grey, w.in.frame.rgb))
    w.res.roi = r->box;
  else
    w.res.roi.reset();
  w.res.times.roi_ms += msSince(t0);
  w.roiDetected = true;
}

void CRgbdOdometry::takeRoi(TFrameWork& w) const
{
  TFrameResult& res = w.res;
  w.roiDetected = w.in.roiDetected;
  if (w.in.roiDetected)
  {
    res.times.roi_ms = w.in.roi_ms;
    if (w.in.roi)
      res.roi = w.in.roi->box;
  }
  if (!followsWithFlow())
    return;
  // The reference keyframe's ROI (its stage-1 ROI, StageKeyframe.cpp), moved
  // by the predicted motion: the landmark stays the one the keyframe
  // described, and stage 1 runs only when it leaves the view and on frames
  // that are no flow frames. With flow_describe_roi = when_weak an ordinary
  // frame needs a ROI only when its anchors leave the pose undetermined, so
  // stage 1 waits for that (describeRoi); a keyframe runs it when stored.
  if (w.flowFrame)
  {
    const TKeyframe& kf = m_keyframes[w.ref];
    const cv::Rect followed =
        detail::followRegion(kf, w.predictedWorld - kf.pose, m_impl->pinhole, w.in.grey.size());
    if (!followed.empty())
      res.roi = followed;
  }
  if (!res.roi && !(w.flowFrame && m_options.flow_describe_roi == "when_weak"))
    detectRoi(w);
}

bool CRgbdOdometry::flowAvailable(const TFrameWork& w) const
{
  return !m_keyframes.empty() && !w.in.flowPyramid.empty() && m_impl->flowPyramids.count(w.ref);
}

void CRgbdOdometry::extractFeatures(TFrameWork& w) const
{
  const TImpl& I = *m_impl;
  TFrameResult& res = w.res;
  const cv::Mat& grey = w.in.grey;
  res.frameIndex = w.in.frame.index;
  res.timestamp = w.in.frame.timestamp;
  res.imageSize = grey.size();
  const auto& o = m_options;
  w.featureImage = w.in.featureGrey.empty()
                       ? detail::workingImage(grey, o.feature_resolution == "auto")
                       : detail::TWorkingImage{w.in.featureGrey, w.in.featureShift, grey.size()};
  // An expected keyframe describes the whole image at once (below).
  w.flowFrame = followsWithFlow() && flowAvailable(w) && !w.keyframeExpected;
  takeRoi(w);
  const auto t0 = Clock::now();
  auto& work = res.work;
  // The region: the reference keyframe's, followed with the predicted
  // motion, so that it stays on the landmark the keyframe described densely;
  // a new one from stage 1 when it is lost (or at the start).
  const double minArea = std::min(1.0, o.roi_min_area_fraction * I.regionGrowth);
  const bool flow = w.flowFrame;
  int regionCap = o.extractor.max_features;
  if (flow)
  {
    // Flow: the optical flow of the reference keyframe's features gives the
    // pose its spread, so the region is the ROI itself, described at the
    // image's feature density (its share of max_features), and a frame
    // without a ROI describes nothing. when_weak: not even the ROI yet
    // (describeRoi, if the anchors alone leave the pose undetermined).
    if (res.roi && o.flow_describe_roi == "always")
      work.region = *res.roi & cv::Rect(cv::Point(0, 0), grey.size());
    else
      w.roiDeferred = res.roi.has_value() || o.flow_describe_roi == "when_weak";
    regionCap = roiFeatureCap(o, work.region, grey.size());
  }
  else
  {
    if (describesRegions() && !m_keyframes.empty())
      work.region = detail::followRegion(
          m_keyframes[w.ref], w.predictedWorld - m_keyframes[w.ref].pose, I.pinhole, grey.size());
    // Its size is the one the registrations ask for now (regionGrowth, from
    // their determinacy), not the keyframe's: it shrinks back after a growth.
    if (!work.region.empty())
      work.region = detail::regionOfArea(work.region, grey.size(), minArea, o.roi_min_aspect);
    if (describesRegions() && work.region.empty() && res.roi)
      work.region = detail::trackingRegion(*res.roi, grey.size(), minArea, o.roi_min_aspect);
  }
  // An expected keyframe keeps its region (the frames after it follow that)
  // but describes the whole image at once.
  if (!work.region.empty() && !w.keyframeExpected)
  {
    w.all =
        detail::extractIn(I.extractor, w.featureImage, work.region, regionCap, &work.regionPixels);
    work.regionFeatures = w.all.size();
    w.regionOnly = true;
  }
  else if (flow)
  {
    w.all.type = o.extractor.feature_type;
    w.regionOnly = true;
  }
  else
  {
    // roi_feature_cap = roi: every detection now, the cap per region below.
    const bool capInRoi = isRoiMode(m_options.mode) && m_options.roi_feature_cap == "roi";
    const cv::Mat& fg = w.featureImage.grey;
    w.all = capInRoi ? I.extractor.extractAll(fg) : I.extractor.extract(fg);
    detail::toImagePixels(w.all, w.featureImage.shift);
    if (capInRoi)
      w.all = I.extractor.capWithRegion(w.all, res.roi.value_or(cv::Rect()));
    work.extensionPixels = static_cast<std::size_t>(fg.total());
    work.extensionFeatures = w.all.size();
    work.extension = !describesRegions()  ? EExtension::WholeImage
                     : w.keyframeExpected ? EExtension::ExpectedKeyframe
                                          : EExtension::NoRoi;
  }
  res.times.extract_ms = msSince(t0);
  res.features = w.all.size();
}

void CRgbdOdometry::liftFeatures(TFrameWork& w) const
{
  const TImpl& I = *m_impl;
  const TOptions& o = m_options;
  TFrameResult& res = w.res;
  const auto t0 = Clock::now();
  // Undistorted pixel + depth at the (distorted) keypoint; depth and rolling
  // shutter, first guess: the velocity of the last motion.
  w.ratePredicted = detail::cameraRate(I.velocity, I.velocityDt);
  w.rateApplied = w.ratePredicted;
  w.lifted = I.lift(w.all, w.in.frame.depth, w.depthDt, w.ratePredicted, o);
  // The corrections never change which keypoints are valid.
  const std::vector<int>& valid = w.lifted.valid;
  res.featuresWithDepth = valid.size();
  // Tracking set: the ROI's subset (the region's features), or the whole image.
  w.chosen = valid;
  if (isRoiMode(o.mode))
  {
    std::vector<int> inRoi;
    if (w.regionOnly || res.roi)
      inRoi = inside(w.all, valid, w.regionOnly ? res.work.region : *res.roi);
    res.roiFeatures = inRoi.size();
    // Flow: few ROI features are no reason to describe more, the followed
    // keyframe features carry the pose.
    const bool flow = w.flowFrame;
    const bool enough = static_cast<int>(inRoi.size()) >= o.min_roi_features;
    // An expected keyframe tracks with the whole image it described, as its
    // keyframe edges would be computed anyway (keyframe_full_registration).
    if (w.keyframeExpected)
      w.fallback = true;
    else if (enough || o.strict_roi || flow)
      w.chosen = std::move(inRoi);  // strict with too few: the frame will be Lost
    else
      w.fallback = true;
    w.flowFallback = flow && !enough && !o.strict_roi && !w.roiDeferred;
    w.strictLost = o.strict_roi && static_cast<int>(res.roiFeatures) < o.min_roi_features;
  }
  // Whole-image set (keyframe storage, fallback) and the set tracked with.
  w.full = frameSet(w, valid);
  w.cur = w.chosen.size() == valid.size() ? w.full : frameSet(w, w.chosen);
  w.cur.fullImageFallback = w.fallback;
  res.trackingFeatures = w.cur.features.size();
  res.times.lift_ms = msSince(t0);
  if (w.fallback && w.regionOnly)
  {
    // Too few features in the region: the whole image tracks this frame.
    extendToImage(w, EExtension::FewRoiFeatures);
    w.cur = w.full;
    w.cur.fullImageFallback = true;
    res.trackingFeatures = w.cur.features.size();
  }
}

void CRgbdOdometry::extendToImage(TFrameWork& w, EExtension reason) const
{
  if (!w.regionOnly)
    return;  // at most once per frame
  w.regionOnly = false;
  const TImpl& I = *m_impl;
  const TOptions& o = m_options;
  TFrameResult& res = w.res;
  auto t0 = Clock::now();
  std::size_t px = 0;
  features::TFeatureSet ext = describeOutside(
      I.extractor, w.featureImage, res.work.region, o.extractor.max_features, o.roi_extension_scale,
      &px);
  ext.type = w.all.type;
  res.work.extensionPixels += px;
  res.work.extensionFeatures = ext.size();
  res.work.extension = reason;
  res.times.extract_ms += msSince(t0);

  // Lifted like the region's, with the rolling-shutter rate they carry now.
  t0 = Clock::now();
  detail::appendLifted(
      w.lifted, I.lift(ext, w.in.frame.depth, w.depthDt, w.rateApplied, o),
      static_cast<int>(w.all.size()));
  w.all = features::concat(w.all, ext);
  const std::vector<int>& valid = w.lifted.valid;
  w.full = frameSet(w, valid);
  res.features = w.all.size();
  res.featuresWithDepth = valid.size();
  res.times.lift_ms += msSince(t0);
}

TKeyframe CRgbdOdometry::frameSet(const TFrameWork& w, const std::vector<int>& idx) const
{
  TKeyframe k = detail::makeFeatureSet(w.all, w.lifted, idx, m_impl->pinhole);
  k.frameIndex = w.in.frame.index;
  k.timestamp = w.in.frame.timestamp;
  k.roi = w.res.roi;
  return k;
}

bool CRgbdOdometry::describeRoi(TFrameWork& w) const
{
  if (!w.roiDeferred || !w.regionOnly)
    return false;
  w.roiDeferred = false;
  const TImpl& I = *m_impl;
  const TOptions& o = m_options;
  TFrameResult& res = w.res;
  // Stage 1 waited for this when the reference keyframe's ROI had left the
  // view (takeRoi).
  if (!res.roi)
    detectRoi(w);
  if (!res.roi)
    return false;
  const cv::Rect roi = *res.roi & cv::Rect(cv::Point(0, 0), w.in.grey.size());
  if (roi.empty())
    return false;
  // Nothing was described before: the ROI's features are the frame's first.
  auto t0 = Clock::now();
  res.work.region = roi;
  w.all = detail::extractIn(
      I.extractor, w.featureImage, roi, roiFeatureCap(o, roi, w.in.grey.size()),
      &res.work.regionPixels);
  res.work.regionFeatures = w.all.size();
  res.times.extract_ms += msSince(t0);

  // Lifted with the rolling-shutter rate the anchors carry now.
  t0 = Clock::now();
  w.lifted = I.lift(w.all, w.in.frame.depth, w.depthDt, w.rateApplied, o);
  w.chosen = inside(w.all, w.lifted.valid, roi);
  res.features = w.all.size();
  res.featuresWithDepth = w.lifted.valid.size();
  res.roiFeatures = w.chosen.size();
  w.full = frameSet(w, w.lifted.valid);
  w.regionSet = frameSet(w, w.chosen);
  if (w.flowRef)
    rebuildFollowedSet(w);
  else
    w.cur = w.regionSet;
  res.trackingFeatures = w.cur.features.size();
  res.times.lift_ms += msSince(t0);
  return true;
}
}  // namespace roislam::frontend
