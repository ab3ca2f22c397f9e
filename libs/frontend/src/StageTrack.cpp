// Stage 3 of the front end: the motion predicted from the last one, then the
// frame's features registered against the recent keyframes (the ROI's first
// in ROI modes, the whole image's when those fail or leave the pose poorly
// determined).
#include <algorithm>

#include "OdometryWork.h"

namespace roislam::frontend
{
void CRgbdOdometry::registerWithRecent(const TKeyframe& query, TFrameWork& w) const
{
  // The last keyframe, then the recent older ones, until one registers.
  const std::size_t nTry = 1 + static_cast<std::size_t>(m_options.recent_keyframes);
  for (std::size_t k = 0; k < nTry && k <= w.lastKf; ++k)
  {
    const std::size_t id = w.lastKf - k;
    std::size_t nm = 0;
    w.reg = m_impl->registerSets(m_keyframes[id], query, m_options, &nm, &w.res.times);
    if (k == 0 || w.reg)
      w.res.matches = nm;
    if (w.reg)
    {
      w.ref = id;
      return;
    }
  }
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
  const mrpt::poses::CPose3D predictedWorld = w.lastWorld + I.velocity;
  w.predictedRel = predictedWorld - m_keyframes[w.lastKf].pose;
}

void CRgbdOdometry::trackFeatures(TFrameWork& w)
{
  const TOptions& o = m_options;
  registerWithRecent(w.cur, w);
  // A ROI registration on few inliers, or one that leaves the pose poorly
  // determined, is kept only when nothing better exists.
  const bool roiTracked = isRoiMode(o.mode) && !o.strict_roi && !w.fallback;
  const bool weakRoi = w.reg && roiTracked && detail::isWeakRoiRegistration(*w.reg, o);
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
  w.cur = w.full;
  w.cur.fullImageFallback = true;
  w.res.trackingFeatures = w.cur.features.size();
}
}  // namespace roislam::frontend
