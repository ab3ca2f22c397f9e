// CRgbdOdometry: construction, the public queries, prepare() (checks and
// stage 1) and process(), which runs the stages in order. The stages are in
// StageExtract.cpp, StageTrack.cpp, StageRefine.cpp, StageBridge.cpp and
// StageKeyframe.cpp.
#include "roislam/frontend/CRgbdOdometry.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <tuple>

#include "OdometryWork.h"

namespace roislam::frontend
{
using detail::Clock;
using detail::msSince;

bool isFeatureMethod(ETrackingMethod m)
{
  return m == ETrackingMethod::Features || m == ETrackingMethod::RoiFeatures ||
         m == ETrackingMethod::Flow || m == ETrackingMethod::FullImageFallback;
}

TInformation66 scaledIdentity(double s)
{
  TInformation66 o;
  o.setZero();
  for (int i = 0; i < 6; ++i)
    o(i, i) = s;
  return o;
}

namespace
{
roi::CRoiDetector::TOptions roiOptionsFor(const CRgbdOdometry::TOptions& o)
{
  roi::CRoiDetector::TOptions r = o.roi;
  if (o.mode == EFrontEndMode::RoiSmall)
    r.setPreset("small");
  else if (o.mode == EFrontEndMode::RoiBig)
    r.setPreset("big");
  return r;
}

matching::CRigidTransformRansac::TOptions ransacOptions(const CRgbdOdometry::TOptions& o)
{
  matching::CRigidTransformRansac::TOptions r;
  r.threshold_m = o.ransac_threshold_m;
  r.max_iterations = o.ransac_max_iterations;
  r.min_inliers = o.min_inliers;
  return r;
}

}  // namespace

CRgbdOdometry::TImpl::TImpl(const TOptions& o)
    : roiDetector(o.roi), extractor(o.extractor), matcher(o.matcher), ransac(ransacOptions(o))
{
}

void CRgbdOdometry::TImpl::useCamera(const mrpt::img::TCamera& cam, const TOptions& o)
{
  // MRPT's comparison: size, intrinsics, distortion and its model (also the
  // names, which at worst costs a rebuild).
  if (haveCamera && camera == cam)
    return;
  camera = cam;
  K = (cv::Mat_<double>(3, 3) << cam.fx(), 0, cam.cx(), 0, cam.fy(), cam.cy(), 0, 0, 1);
  dist = cv::Mat(1, 5, CV_64F);
  for (int i = 0; i < 5; ++i)
    dist.at<double>(0, i) = cam.dist[static_cast<std::size_t>(i)];
  pinhole = {cam.fx(), cam.fy(), cam.cx(), cam.cy()};
  detail::CDepthIcp::TParams ip;
  // A camera wider than 1280 px samples its depth as sparsely as a 640 x 480
  // one does (the flow's and the features' rule, FlowTracking.h): at 1920 x
  // 1080 every 4th pixel was 130 000 points and 86 ms an ICP (rgbd-simul).
  ip.decimation = o.icp_decimation << detail::flowShift(
                      cv::Size(static_cast<int>(cam.ncols), static_cast<int>(cam.nrows)));
  ip.maxIterations = o.icp_max_iterations;
  ip.convergedStepSigma = o.icp_converged_step_sigma;
  ip.maxDistance = o.icp_max_distance_m;
  ip.minPairs = o.icp_min_pairs;
  ip.minDepth = o.min_depth_m;
  ip.maxDepth = o.max_depth_m;
  icp = std::make_unique<detail::CDepthIcp>(ip, cam);
  icpMaps.clear();
  photoKeyframes.clear();
  haveCamera = true;
}

ETrackingMethod CRgbdOdometry::featureMethodOf(const TFrameWork& w) const
{
  if (!isRoiMode(m_options.mode))
    return ETrackingMethod::Features;
  // A frame expected to become a keyframe (keyframe_prediction) describes
  // and tracks with the whole image by design, not for want of a ROI.
  if (w.keyframeExpected)
    return ETrackingMethod::Features;
  if (w.fallback)
    return ETrackingMethod::FullImageFallback;
  // Followed anchors without (enough of) the ROI's features.
  if (w.flowRef && (w.flowFallback || w.regionSet.features.empty()))
    return ETrackingMethod::Flow;
  return ETrackingMethod::RoiFeatures;
}

std::optional<detail::TRegistration> CRgbdOdometry::TImpl::registerSets(
    const TKeyframe& ref, const TKeyframe& cur, const TOptions& o, std::size_t* matchesOut,
    TStageTimes* times, const detail::TKnownPairs* known) const
{
  return detail::registerSets(
      ref, cur, matcher, ransac, pinhole, o, matchesOut, times ? &times->match_ms : nullptr,
      times ? &times->ransac_ms : nullptr, known);
}

CRgbdOdometry::CRgbdOdometry() : CRgbdOdometry(TOptions()) {}

CRgbdOdometry::CRgbdOdometry(const TOptions& options)
    : mrpt::system::COutputLogger("CRgbdOdometry"), m_options(options)
{
  m_options.validate();
  m_options.roi = roiOptionsFor(m_options);
  m_impl = std::make_unique<TImpl>(m_options);
}

CRgbdOdometry::~CRgbdOdometry() = default;

const TKeyframe& CRgbdOdometry::keyframe(std::size_t id) const
{
  if (id >= m_keyframes.size())
    throw std::out_of_range("CRgbdOdometry: no keyframe " + std::to_string(id));
  return m_keyframes[id];
}

void CRgbdOdometry::correctKeyframePoses(const std::map<std::size_t, mrpt::poses::CPose3D>& poses)
{
  for (const auto& [id, pose] : poses)
    if (id < m_keyframes.size())
      m_keyframes[id].pose = pose;
}

void CRgbdOdometry::reset()
{
  m_keyframes.clear();
  m_stats = TStats();
  m_impl->icpMaps.clear();
  m_impl->photoKeyframes.clear();
  m_impl->flowPyramids.clear();
  m_impl->haveLast = false;
  m_impl->velocity = mrpt::poses::CPose3D();
  m_impl->velocityDt = 0;
  m_impl->haveStamp = false;
  m_impl->uncorrected.reset();
  m_impl->depthTime.reset();
  m_impl->icpConsistency.reset();
  m_impl->framesSinceIcp = 0;
  m_impl->regionGrowth = 1;
  m_impl->bestInliers.clear();
  m_impl->atInlierFloor.clear();
  m_impl->lastFeaturePixels.clear();
}

std::optional<TRelativePoseEstimate> CRgbdOdometry::registerKeyframes(
    std::size_t idA, std::size_t idB) const
{
  const TKeyframe& A = keyframe(idA);
  const TKeyframe& B = keyframe(idB);
  if (!m_impl->haveCamera)
    return std::nullopt;
  const auto r = m_impl->registerSets(A, B, m_options);
  if (!r)
    return std::nullopt;
  TRelativePoseEstimate e;
  std::tie(e.pose, e.information) = detail::toMrptEstimate(*r);
  e.edgeInformation = detail::toSpaEstimate(*r);
  e.matches = r->matches;
  e.inliers = r->inliers;
  e.rmse_m = r->rmse3d;
  e.rmse_px = r->rmsePx;
  return e;
}

TPreparedFrame CRgbdOdometry::prepare(const io::TRGBDFrame& frame) const
{
  if (frame.rgb.empty() || frame.rgb.type() != CV_8UC3)
    throw std::invalid_argument("CRgbdOdometry::process: rgb must be a CV_8UC3 image");
  if (frame.depth.type() != CV_32FC1 || frame.depth.size() != frame.rgb.size())
    throw std::invalid_argument(
        "CRgbdOdometry::process: depth must be CV_32FC1 of the colour image's size");
  if (static_cast<int>(frame.camera.ncols) != frame.rgb.cols ||
      static_cast<int>(frame.camera.nrows) != frame.rgb.rows)
    throw std::invalid_argument("CRgbdOdometry::process: camera size differs from the images");
  TPreparedFrame p;
  p.frame = frame;
  if (!frame.depth.isContinuous())
    p.frame.depth = frame.depth.clone();
  const auto t0 = Clock::now();
  cv::cvtColor(frame.rgb, p.grey, cv::COLOR_BGR2GRAY);
  // Stage 1: the ROI (traditional mode: only for keyframes, StageKeyframe.cpp;
  // flow: only where the reference keyframe's ROI cannot be followed,
  // StageExtract.cpp, and for keyframes).
  if (isRoiMode(m_options.mode) && !followsWithFlow())
  {
    p.roi = m_impl->roiDetector.detect(p.grey, frame.rgb);
    p.roiDetected = true;
    p.roi_ms = msSince(t0);
  }
  const auto work = detail::workingImage(p.grey, m_options.feature_resolution == "auto");
  p.featureGrey = work.grey;
  p.featureShift = work.shift;
  if (followsWithFlow())
    p.flowPyramid = detail::flowPyramidOf(p.grey, work, m_impl->flowParams, false);
  p.prepare_ms = msSince(t0);
  return p;
}

TFrameResult CRgbdOdometry::process(const TPreparedFrame& frame)
{
  m_impl->useCamera(frame.frame.camera, m_options);
  TFrameWork w(frame);
  // A frame without a depth stamp of its own (a rawlog's observation has one
  // stamp) has no offset.
  const io::TRGBDFrame& f = frame.frame;
  if (m_options.depth_time_correction && f.depthTimestamp != 0)
    w.depthDt = m_impl->depthTime.update(f.timestamp, f.depthTimestamp);
  if (!m_keyframes.empty())
  {
    predictMotion(w);
    w.keyframeExpected = expectsKeyframe(w);
  }
  extractFeatures(w);
  liftFeatures(w);
  if (m_keyframes.empty() || w.strictLost)
  {
    m_impl->previous.reset();
    startMap(w);
    return finish(w);
  }
  trackFeatures(w);
  rescueWithAnchors(w);
  refineRollingShutter(w);
  refineWithDepth(w);
  if (!resolvePose(w))
  {
    m_impl->previous.reset();
    return finish(w);
  }
  if (!needsKeyframe(w))
  {
    m_impl->haveLast = true;
    m_impl->lastRef = w.ref;
    m_impl->lastRel = w.res.relativePose;
    if (isFeatureMethod(w.res.method))
    {
      std::size_t& best = m_impl->bestInliers[w.ref];
      best = std::max(best, w.res.inliers);
      if (static_cast<int>(w.res.inliers) >= m_options.keyframe_min_inliers)
        m_impl->atInlierFloor.insert(w.ref);
    }
    rememberFrame(w);
    return finish(w);
  }
  // Keyframes store (and register) the whole image's features.
  if (m_options.keyframe_full_features)
    extendToImage(w, EExtension::Keyframe);
  makeKeyframeConstraints(w);
  insertKeyframe(w, *w.res.pose);
  m_impl->previous.reset();
  return finish(w);
}

const std::vector<cv::Point2f>& CRgbdOdometry::lastFeaturePixels() const
{
  return m_impl->lastFeaturePixels;
}

TFrameResult CRgbdOdometry::finish(TFrameWork& w)
{
  TFrameResult& res = w.res;
  res.times.total_ms = w.in.prepare_ms + msSince(w.start);
  m_impl->lastFeaturePixels.clear();
  for (const auto& kp : w.all.keypoints)
    m_impl->lastFeaturePixels.push_back(kp.pt);
  if (res.pose)
  {
    m_impl->lastStamp = w.in.frame.timestamp;
    m_impl->haveStamp = true;
  }
  ++m_stats.frames;
  if (isRoiMode(m_options.mode) && w.roiDetected && !res.roi)
    ++m_stats.noRoi;
  ++m_stats.extensions[res.work.extension];
  m_stats.describedFractionSum += res.work.describedFraction(res.imageSize);
  if (res.icpRefined)
    ++m_stats.icpRefined;
  if (res.icpOverruledFeatures)
    ++m_stats.icpOverruledFeatures;
  if (res.icpReplacedFeatures)
    ++m_stats.icpReplacedFeatures;
  if (res.featureScale > 0)
  {
    m_stats.featureScale = res.featureScale;
    m_stats.icpJointScale = res.icpJointScale;
  }
  res.bridged = w.bridged;
  if (w.bridged)
    ++m_stats.bridged;
  m_stats.bridgedConstraints += res.bridgedConstraints;
  switch (res.method)
  {
    case ETrackingMethod::Initial:
      ++m_stats.initial;
      break;
    case ETrackingMethod::Features:
      ++m_stats.features;
      break;
    case ETrackingMethod::RoiFeatures:
      ++m_stats.roiFeatures;
      break;
    case ETrackingMethod::Flow:
      ++m_stats.flow;
      break;
    case ETrackingMethod::FullImageFallback:
      ++m_stats.fullImageFallback;
      break;
    case ETrackingMethod::DepthIcp:
      ++m_stats.depthIcp;
      break;
    case ETrackingMethod::ConstantVelocity:
      ++m_stats.constantVelocity;
      break;
    case ETrackingMethod::Lost:
      ++m_stats.lost;
      break;
  }
  return std::move(res);
}
}  // namespace roislam::frontend
