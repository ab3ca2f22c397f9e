// The previous-frame bridge (bridge_previous_frame): a frame whose features
// no longer register against the keyframe the previous frame tracked is
// registered against that previous frame, and the two registrations are
// chained. Without it, a keyframe made from a blurred frame (by depth ICP,
// its features matching nothing older) was tracked well by the next frames
// and then left behind with its one edge: on fr1/rpy its frames were 20-45
// mm off. Off in the library, on in the shipped configs (README "A keyframe
// where the ROI weakens"). Where depth ICP is available too, the better
// determined of the chain and ICP is kept (resolvePose, StageRefine.cpp).
#include "OdometryWork.h"

namespace roislam::frontend
{
namespace
{
/** The frame's described features with the most of them: the whole
 *  image's once described, else the tracked set without followed anchors
 *  (those carry no descriptors). */
const TKeyframe& describedSet(const TKeyframe& full, const TKeyframe& tracked)
{
  return full.features.size() > tracked.features.size() ? full : tracked;
}

bool tracksWithDescriptors(ETrackingMethod m)
{
  return m == ETrackingMethod::Features || m == ETrackingMethod::RoiFeatures ||
         m == ETrackingMethod::FullImageFallback;
}
}  // namespace

std::optional<detail::TRegistration> CRgbdOdometry::TImpl::chainedThroughPrevious(
    const TKeyframe& query, const TOptions& o, std::size_t* matchesOut, TStageTimes* times) const
{
  if (!previous)
    return std::nullopt;
  const auto r = registerSets(previous->set, query, o, matchesOut, times);
  if (!r)
    return std::nullopt;
  return detail::chainRegistrations(previous->reg, *r);
}

bool CRgbdOdometry::bridgeFromPrevious(TFrameWork& w) const
{
  const TImpl& I = *m_impl;
  std::size_t matches = 0;
  auto chained = I.chainedThroughPrevious(
      describedSet(w.full, w.flowRef ? w.regionSet : w.cur), m_options, &matches, &w.res.times);
  if (!chained)
    return false;
  w.reg = std::move(chained);
  w.ref = I.previous->ref;
  w.res.matches = matches;
  w.bridged = true;
  return true;
}

void CRgbdOdometry::rememberFrame(TFrameWork& w)
{
  TImpl& I = *m_impl;
  I.previous.reset();
  if (!m_options.bridge_previous_frame || (m_options.strict_roi && isRoiMode(m_options.mode)) ||
      !w.reg || w.bridged || !tracksWithDescriptors(w.res.method))
    return;
  TKeyframe& set = w.flowRef ? w.regionSet : w.cur;
  if (set.features.size() < static_cast<std::size_t>(m_options.min_inliers))
    return;
  // Its search index is built when a frame needs it (rarely).
  set.index.reset();
  I.previous = detail::TTrackedFrame{std::move(set), w.ref, *w.reg};
}
}  // namespace roislam::frontend
