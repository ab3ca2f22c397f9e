// Stage 2 and lifting of the front end. ROI modes describe features in the
// tracking region (the ROI grown to track with) and extend to the rest of
// the image only when the frame needs it; traditional mode (and strict_roi,
// roi_extraction = image) describes the whole image once, the ROI selecting
// its subset. Keypoints are lifted to 3-D with the registered depth and
// corrected for the rolling shutter with the last motion's velocity.
#include <algorithm>
#include <cmath>

#include "OdometryWork.h"
#include "TrackingRegion.h"

namespace roislam::frontend
{
using detail::Clock;
using detail::msSince;

bool CRgbdOdometry::describesRegions() const
{
  return isRoiMode(m_options.mode) && !m_options.strict_roi && m_options.roi_extraction == "region";
}

void CRgbdOdometry::extractFeatures(TFrameWork& w) const
{
  const TImpl& I = *m_impl;
  TFrameResult& res = w.res;
  const cv::Mat& grey = w.in.grey;
  res.frameIndex = w.in.frame.index;
  res.timestamp = w.in.frame.timestamp;
  res.imageSize = grey.size();
  if (w.in.roiDetected)
  {
    res.times.roi_ms = w.in.roi_ms;
    if (w.in.roi)
      res.roi = w.in.roi->box;
  }
  const auto t0 = Clock::now();
  auto& work = res.work;
  // The region: the reference keyframe's, followed with the predicted
  // motion, so that it stays on the landmark the keyframe described densely;
  // a new one from stage 1 when it is lost (or at the start).
  const auto& o = m_options;
  const double minArea = std::min(1.0, o.roi_min_area_fraction * I.regionGrowth);
  if (describesRegions() && !m_keyframes.empty())
    work.region =
        detail::followRegion(m_keyframes[w.lastKf], w.predictedRel, I.pinhole, grey.size());
  if (!work.region.empty())
    work.region = detail::trackingRegion(work.region, grey.size(), minArea, o.roi_min_aspect);
  if (describesRegions() && work.region.empty() && res.roi)
    work.region =
        detail::trackingRegion(*res.roi, grey.size(), o.roi_min_area_fraction, o.roi_min_aspect);
  if (!work.region.empty())
  {
    w.all = I.extractor.extractIn(
        grey, work.region, m_options.extractor.max_features, &work.regionPixels);
    work.regionFeatures = w.all.size();
    w.regionOnly = true;
  }
  else
  {
    // roi_feature_cap = roi: every detection now, the cap per region below.
    const bool capInRoi = isRoiMode(m_options.mode) && m_options.roi_feature_cap == "roi";
    w.all = capInRoi ? I.extractor.extractAll(grey) : I.extractor.extract(grey);
    if (capInRoi)
      w.all = I.extractor.capWithRegion(w.all, res.roi.value_or(cv::Rect()));
    work.extensionPixels = static_cast<std::size_t>(grey.total());
    work.extensionFeatures = w.all.size();
    work.extension = describesRegions() ? EExtension::NoRoi : EExtension::WholeImage;
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
  // Undistorted pixel + depth at the (distorted) keypoint.
  w.lifted = detail::liftFeatures(w.all, w.in.frame.depth, I.K, I.dist, o);
  // Rolling shutter, first guess: the velocity of the last motion.
  w.ratePredicted = detail::cameraRate(I.velocity, I.velocityDt);
  w.rateApplied = w.ratePredicted;
  detail::rectifyRollingShutter(w.lifted, w.ratePredicted, o.rolling_shutter_ms * 1e-3, I.pinhole);
  // The corrections never change which keypoints are valid.
  const std::vector<int>& valid = w.lifted.valid;
  res.featuresWithDepth = valid.size();
  // Tracking set: the ROI's subset (the region's features), or the whole image.
  w.chosen = valid;
  if (isRoiMode(o.mode))
  {
    std::vector<int> inRoi;
    if (w.regionOnly || res.roi)
    {
      const cv::Rect2f box(w.regionOnly ? res.work.region : *res.roi);
      for (int i : valid)
        if (box.contains(w.all.keypoints[static_cast<std::size_t>(i)].pt))
          inRoi.push_back(i);
    }
    res.roiFeatures = inRoi.size();
    if (static_cast<int>(inRoi.size()) >= o.min_roi_features || o.strict_roi)
      w.chosen = std::move(inRoi);  // strict with too few: the frame will be Lost
    else
      w.fallback = true;
    w.strictLost = o.strict_roi && static_cast<int>(res.roiFeatures) < o.min_roi_features;
  }
  auto makeSet = [&](const std::vector<int>& idx)
  {
    TKeyframe k = detail::makeFeatureSet(w.all, w.lifted, idx, I.pinhole);
    k.frameIndex = w.in.frame.index;
    k.timestamp = w.in.frame.timestamp;
    k.roi = res.roi;
    return k;
  };
  // Whole-image set (keyframe storage, fallback) and the set tracked with.
  w.full = makeSet(valid);
  w.cur = w.chosen.size() == valid.size() ? w.full : makeSet(w.chosen);
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
  // The rest of the image, band by band, with the cap's share of each band's
  // area: the region's pixels are never described again.
  const cv::Size image = w.in.grey.size();
  const int cap = o.extractor.max_features;
  features::TFeatureSet ext;
  ext.type = w.all.type;
  for (const cv::Rect& band : detail::outside(res.work.region, image))
  {
    const int bandCap =
        cap > 0 ? std::max(
                      1, static_cast<int>(
                             std::ceil(cap * static_cast<double>(band.area()) / image.area())))
                : 0;
    std::size_t px = 0;
    ext = features::concat(ext, I.extractor.extractIn(w.in.grey, band, bandCap, &px));
    res.work.extensionPixels += px;
  }
  res.work.extensionFeatures = ext.size();
  res.work.extension = reason;
  res.times.extract_ms += msSince(t0);

  // Lifted like the region's, with the rolling-shutter rate they carry now.
  t0 = Clock::now();
  detail::TLiftedFeatures lifted = detail::liftFeatures(ext, w.in.frame.depth, I.K, I.dist, o);
  detail::rectifyRollingShutter(lifted, w.rateApplied, o.rolling_shutter_ms * 1e-3, I.pinhole);
  detail::appendLifted(w.lifted, lifted, static_cast<int>(w.all.size()));
  w.all = features::concat(w.all, ext);
  const std::vector<int>& valid = w.lifted.valid;
  TKeyframe full = detail::makeFeatureSet(w.all, w.lifted, valid, I.pinhole);
  full.frameIndex = w.full.frameIndex;
  full.timestamp = w.full.timestamp;
  full.roi = w.full.roi;
  w.full = std::move(full);
  res.features = w.all.size();
  res.featuresWithDepth = valid.size();
  res.times.lift_ms += msSince(t0);
}
}  // namespace roislam::frontend
