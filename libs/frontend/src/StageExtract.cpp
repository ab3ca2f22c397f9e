// Stages 2 and lifting of the front end: features extracted once per frame
// (the ROI selects its subset), then lifted to 3-D with the registered depth
// and corrected for the rolling shutter with the last motion's velocity.
#include "OdometryWork.h"

namespace roislam::frontend
{
using detail::Clock;
using detail::msSince;

void CRgbdOdometry::extractFeatures(TFrameWork& w) const
{
  const TImpl& I = *m_impl;
  TFrameResult& res = w.res;
  res.frameIndex = w.in.frame.index;
  res.timestamp = w.in.frame.timestamp;
  if (w.in.roiDetected)
  {
    res.times.roi_ms = w.in.roi_ms;
    if (w.in.roi)
      res.roi = w.in.roi->box;
  }
  // roi_feature_cap = roi: every detection now, the cap per region below.
  const bool capInRoi = isRoiMode(m_options.mode) && m_options.roi_feature_cap == "roi";
  const auto t0 = Clock::now();
  w.all = capInRoi ? I.extractor.extractAll(w.in.grey) : I.extractor.extract(w.in.grey);
  if (capInRoi)
    w.all = I.extractor.capWithRegion(w.all, res.roi.value_or(cv::Rect()));
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
  detail::rectifyRollingShutter(w.lifted, w.ratePredicted, o.rolling_shutter_ms * 1e-3, I.pinhole);
  // The corrections never change which keypoints are valid.
  const std::vector<int>& valid = w.lifted.valid;
  res.featuresWithDepth = valid.size();
  // Tracking set: the ROI's subset, or the whole image.
  w.chosen = valid;
  if (isRoiMode(o.mode))
  {
    std::vector<int> inRoi;
    if (res.roi)
    {
      const cv::Rect2f box(*res.roi);
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
}
}  // namespace roislam::frontend
