#include "roislam/frontend/CRgbdOdometry.h"

#include <mrpt/config/CConfigFileBase.h>
#include <roislam/common/IniErrors.h>
#include <roislam/frontend/PoseUncertainty.h>
#include <roislam/matching/CRigidTransformRansac.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <future>
#include <map>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <tuple>

#include "CDepthIcp.h"
#include "FeatureLifting.h"
#include "KeyframeRegistration.h"
#include "ReprojectionRefinement.h"
#include "RigidMath.h"
#include "RollingShutter.h"
#include "Timing.h"

namespace roislam::frontend
{
using detail::Matrix6d;
using detail::rotationAngle;
using detail::TRigid;

using detail::Clock;
using detail::isWeakRoiRegistration;
using detail::lessDetermined;
using detail::msSince;
using detail::registerSets;
using detail::toMrptEstimate;
using detail::TRegistration;

namespace
{

/** Stage 1 on one image of a frame, timed (CRgbdOdometry::TRoiHint). */
CRgbdOdometry::TRoiHint detectTimed(
    const roi::CRoiDetector& detector, const io::TRGBDFrame& frame, const cv::Mat& image)
{
  const auto t0 = Clock::now();
  CRgbdOdometry::TRoiHint h;
  h.frameIndex = frame.index;
  h.timestamp = frame.timestamp;
  if (image.channels() == 3)
  {
    cv::cvtColor(image, h.grey, cv::COLOR_BGR2GRAY);
    h.roi = detector.detect(h.grey, image);
  }
  else
    h.roi = detector.detect(image);
  h.ms = msSince(t0);
  return h;
}

TInformation66 scaledIdentity(double s)
{
  TInformation66 o;
  o.setZero();
  for (int i = 0; i < 6; ++i)
    o(i, i) = s;
  return o;
}

ETrackingMethod featureMethod(EFrontEndMode mode, bool fallback)
{
  if (!isRoiMode(mode))
    return ETrackingMethod::Features;
  return fallback ? ETrackingMethod::FullImageFallback : ETrackingMethod::RoiFeatures;
}

bool isFeatureMethod(ETrackingMethod m)
{
  return m == ETrackingMethod::Features || m == ETrackingMethod::RoiFeatures ||
         m == ETrackingMethod::FullImageFallback;
}
}  // namespace

// ---------------------------------------------------------------- implementation
struct CRgbdOdometry::TImpl
{
  roi::CRoiDetector roiDetector;
  features::CFeatureExtractor extractor;
  matching::CFeatureMatcher matcher;
  matching::CRigidTransformRansac ransac;

  // Camera-dependent state, rebuilt when the intrinsics change.
  bool haveCamera = false;
  mrpt::img::TCamera camera;
  cv::Mat K, dist;
  detail::TPinhole pinhole;
  std::unique_ptr<detail::CDepthIcp> icp;
  /** ICP maps of the most recent keyframes only (memory). */
  std::map<std::size_t, detail::CDepthIcp::TMap> icpMaps;

  // Tracking state: the last tracked (non-lost) frame relative to a keyframe.
  bool haveLast = false;
  std::size_t lastRef = 0;
  mrpt::poses::CPose3D lastRel;
  /** Motion between the last two tracked frames: P_k = P_{k-1} (+) velocity. */
  mrpt::poses::CPose3D velocity;
  /** Colour stamp of the last tracked frame; the interval velocity spans
   *  (0 = unknown). */
  double lastStamp = 0, velocityDt = 0;
  bool haveStamp = false;
  /** The first keyframe is made before any velocity is known: its raw
   *  points wait here until the next frame measures one (rolling shutter). */
  std::optional<detail::TUncorrectedKeyframe> uncorrected;

  TImpl(const TOptions& o)
      : roiDetector(o.roi), extractor(o.extractor), matcher(o.matcher), ransac(ransacOptions(o))
  {
  }

  static matching::CRigidTransformRansac::TOptions ransacOptions(const TOptions& o)
  {
    matching::CRigidTransformRansac::TOptions r;
    r.threshold_m = o.ransac_threshold_m;
    r.max_iterations = o.ransac_max_iterations;
    r.min_inliers = o.min_inliers;
    return r;
  }
};

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

bool sameCamera(const mrpt::img::TCamera& a, const mrpt::img::TCamera& b)
{
  return a.ncols == b.ncols && a.nrows == b.nrows && a.fx() == b.fx() && a.fy() == b.fy() &&
         a.cx() == b.cx() && a.cy() == b.cy() && a.dist == b.dist;
}
}  // namespace

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

void CRgbdOdometry::setKeyframePose(std::size_t id, const mrpt::poses::CPose3D& pose)
{
  if (id >= m_keyframes.size())
    throw std::out_of_range("CRgbdOdometry::setKeyframePose: no keyframe " + std::to_string(id));
  m_keyframes[id].pose = pose;
}

void CRgbdOdometry::reset()
{
  m_keyframes.clear();
  m_stats = TStats();
  m_impl->icpMaps.clear();
  m_impl->haveLast = false;
  m_impl->velocity = mrpt::poses::CPose3D();
  m_impl->velocityDt = 0;
  m_impl->haveStamp = false;
  m_impl->uncorrected.reset();
}

std::optional<TRelativePoseEstimate> CRgbdOdometry::registerKeyframes(
    std::size_t idA, std::size_t idB) const
{
  const TKeyframe& A = keyframe(idA);
  const TKeyframe& B = keyframe(idB);
  if (!m_impl->haveCamera)
    return std::nullopt;
  const auto r = registerSets(
      A, B, m_impl->matcher, m_impl->ransac, m_impl->pinhole, m_options, nullptr, nullptr, nullptr);
  if (!r)
    return std::nullopt;
  TRelativePoseEstimate e;
  std::tie(e.pose, e.information) = toMrptEstimate(*r);
  e.matches = r->matches;
  e.inliers = r->inliers;
  e.rmse_m = r->rmse3d;
  e.rmse_px = r->rmsePx;
  return e;
}

CRgbdOdometry::TRoiHint CRgbdOdometry::detectRoiAhead(const io::TRGBDFrame& frame) const
{
  return detectTimed(m_impl->roiDetector, frame, frame.rgb);
}

TFrameResult CRgbdOdometry::process(
    const io::TRGBDFrame& frame, const std::optional<TRoiHint>& roiHint)
{
  const auto tStart = Clock::now();
  TImpl& I = *m_impl;
  const TOptions& o = m_options;
  if (frame.rgb.empty() || frame.rgb.type() != CV_8UC3)
    throw std::invalid_argument("CRgbdOdometry::process: rgb must be a CV_8UC3 image");
  if (frame.depth.type() != CV_32FC1 || frame.depth.size() != frame.rgb.size())
    throw std::invalid_argument(
        "CRgbdOdometry::process: depth must be CV_32FC1 of the colour image's size");
  if (!I.haveCamera || !sameCamera(I.camera, frame.camera))
  {
    if (static_cast<int>(frame.camera.ncols) != frame.rgb.cols ||
        static_cast<int>(frame.camera.nrows) != frame.rgb.rows)
      throw std::invalid_argument("CRgbdOdometry::process: camera size differs from the images");
    I.camera = frame.camera;
    I.K =
        (cv::Mat_<double>(3, 3) << frame.camera.fx(), 0, frame.camera.cx(), 0, frame.camera.fy(),
         frame.camera.cy(), 0, 0, 1);
    I.dist = cv::Mat(1, 5, CV_64F);
    for (int i = 0; i < 5; ++i)
      I.dist.at<double>(0, i) = frame.camera.dist[static_cast<std::size_t>(i)];
    I.pinhole = {frame.camera.fx(), frame.camera.fy(), frame.camera.cx(), frame.camera.cy()};
    detail::CDepthIcp::TParams ip;
    ip.decimation = o.icp_decimation;
    ip.maxIterations = o.icp_max_iterations;
    ip.maxDistance = o.icp_max_distance_m;
    ip.minPairs = o.icp_min_pairs;
    ip.minDepth = o.min_depth_m;
    ip.maxDepth = o.max_depth_m;
    I.icp = std::make_unique<detail::CDepthIcp>(ip, frame.camera);
    I.icpMaps.clear();
    I.haveCamera = true;
  }
  const cv::Mat depth = frame.depth.isContinuous() ? frame.depth : frame.depth.clone();

  TFrameResult res;
  res.frameIndex = frame.index;
  res.timestamp = frame.timestamp;
  ++m_stats.frames;

  // Stages 1 and 2 are independent (both read the grey image): the ROI is
  // detected on a second thread while the features are extracted, so that on
  // a multi-core CPU the ROI costs no wall time. Features are extracted once,
  // on the whole image.
  std::future<TRoiHint> roiJob;
  const bool useHint = isRoiMode(o.mode) && roiHint && roiHint->frameIndex == frame.index &&
                       roiHint->timestamp == frame.timestamp;
  // The hint's grey image is this frame's, converted on the thread ahead.
  cv::Mat grey;
  if (useHint && roiHint->grey.size() == frame.rgb.size() && roiHint->grey.type() == CV_8UC1)
    grey = roiHint->grey;
  else
    cv::cvtColor(frame.rgb, grey, cv::COLOR_BGR2GRAY);
  if (isRoiMode(o.mode) && !useHint)
    roiJob = std::async(
        std::launch::async,
        [&I, &frame, &grey]() { return detectTimed(I.roiDetector, frame, grey); });
  // roi_feature_cap = roi: every detection now, the cap per region below.
  const bool capInRoi = isRoiMode(o.mode) && o.roi_feature_cap == "roi";
  auto t0 = Clock::now();
  features::TFeatureSet all = capInRoi ? I.extractor.extractAll(grey) : I.extractor.extract(grey);
  res.times.extract_ms = msSince(t0);
  if (roiJob.valid() || useHint)
  {
    const TRoiHint h = useHint ? *roiHint : roiJob.get();
    res.times.roi_ms = h.ms;
    if (h.roi)
      res.roi = h.roi->box;
    else
      ++m_stats.noRoi;
  }
  if (capInRoi)
  {
    t0 = Clock::now();
    all = I.extractor.capWithRegion(all, res.roi.value_or(cv::Rect()));
    res.times.extract_ms += msSince(t0);
  }
  res.features = all.size();

  // Lift to 3-D: undistorted pixel + depth at the (distorted) keypoint.
  t0 = Clock::now();
  detail::TLiftedFeatures lifted = detail::liftFeatures(all, depth, I.K, I.dist, o);
  // The corrections below change points and pixels, never which are valid.
  const std::vector<int>& valid = lifted.valid;
  // Rolling shutter, first guess: the velocity of the last motion.
  const double readout = o.rolling_shutter_ms * 1e-3;
  const detail::TCameraRate ratePredicted = detail::cameraRate(I.velocity, I.velocityDt);
  detail::rectifyRollingShutter(lifted, ratePredicted, readout, I.pinhole);
  res.featuresWithDepth = valid.size();
  // Tracking set: ROI subset or the whole image.
  std::vector<int> chosen = valid;
  bool fallback = false;
  if (isRoiMode(o.mode))
  {
    std::vector<int> inRoi;
    if (res.roi)
    {
      const cv::Rect2f box(*res.roi);
      for (int i : valid)
        if (box.contains(all.keypoints[static_cast<std::size_t>(i)].pt))
          inRoi.push_back(i);
    }
    res.roiFeatures = inRoi.size();
    if (static_cast<int>(inRoi.size()) >= o.min_roi_features)
      chosen = std::move(inRoi);
    else if (o.strict_roi)
      chosen = std::move(inRoi);  // too few: the frame will be Lost
    else
      fallback = true;
  }
  auto makeSet = [&](const std::vector<int>& idx)
  {
    TKeyframe k = detail::makeFeatureSet(all, lifted, idx, I.pinhole);
    k.frameIndex = frame.index;
    k.timestamp = frame.timestamp;
    k.roi = res.roi;
    return k;
  };
  // Whole-image set (keyframe storage, fallback) and the set tracked with.
  TKeyframe full = makeSet(valid);
  TKeyframe cur = chosen.size() == valid.size() ? full : makeSet(chosen);
  cur.fullImageFallback = fallback;
  res.trackingFeatures = cur.features.size();
  res.times.lift_ms = msSince(t0);

  const bool strictLost =
      isRoiMode(o.mode) && o.strict_roi && static_cast<int>(res.roiFeatures) < o.min_roi_features;

  auto finish = [&]()
  {
    res.times.total_ms = msSince(tStart);
    if (res.pose)
    {
      I.lastStamp = frame.timestamp;
      I.haveStamp = true;
    }
    if (res.icpRefined)
      ++m_stats.icpRefined;
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
    return res;
  };

  auto addKeyframe = [&](const mrpt::poses::CPose3D& pose)
  {
    const auto tk = Clock::now();
    // Stored for later matching: the whole image's features (unless
    // keyframe_full_features is off), so that the next frames' ROI, which
    // moves and changes size, still finds its partners.
    TKeyframe& kf = o.keyframe_full_features ? full : cur;
    kf.fullImageFallback = fallback;
    kf.id = m_keyframes.size();
    kf.pose = pose;
    m_keyframes.push_back(std::move(kf));
    ++m_stats.keyframes;
    res.isNewKeyframe = true;
    res.newKeyframeId = m_keyframes.back().id;
    I.icpMaps[res.newKeyframeId] = I.icp->buildMap(depth);
    I.uncorrected.reset();
    if (readout != 0 && !(I.velocityDt > 0))
      I.uncorrected = detail::uncorrectedKeyframe(
          res.newKeyframeId, lifted, o.keyframe_full_features || fallback ? valid : chosen);
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
    res.times.icp_ms += msSince(tk);
  };

  // First frame: the map's origin.
  if (m_keyframes.empty())
  {
    if (strictLost)
    {
      res.method = ETrackingMethod::Lost;
      return finish();
    }
    res.method = ETrackingMethod::Initial;
    res.pose = m_initialPose;
    res.relativeInformation = scaledIdentity(1e6);
    addKeyframe(m_initialPose);
    return finish();
  }
  if (strictLost)
  {
    res.method = ETrackingMethod::Lost;
    return finish();
  }

  const std::size_t lastKf = m_keyframes.size() - 1;
  auto setVelocity = [&](const mrpt::poses::CPose3D& v)
  {
    I.velocity = v;
    I.velocityDt = I.haveStamp ? frame.timestamp - I.lastStamp : 0;
  };
  // Prediction (constant velocity) relative to the last keyframe.
  mrpt::poses::CPose3D lastWorld = m_keyframes[lastKf].pose;
  if (I.haveLast)
    lastWorld = m_keyframes[I.lastRef].pose + I.lastRel;
  const mrpt::poses::CPose3D predictedWorld = lastWorld + I.velocity;
  const mrpt::poses::CPose3D predictedRel = predictedWorld - m_keyframes[lastKf].pose;

  // Features against the last keyframe, then the recent older ones.
  std::optional<TRegistration> reg;
  std::size_t ref = lastKf;
  auto track = [&](const TKeyframe& query)
  {
    const std::size_t nTry = 1 + static_cast<std::size_t>(o.recent_keyframes);
    for (std::size_t k = 0; k < nTry && k <= lastKf; ++k)
    {
      const std::size_t id = lastKf - k;
      std::size_t nm = 0;
      reg = registerSets(
          m_keyframes[id], query, I.matcher, I.ransac, I.pinhole, o, &nm, &res.times.match_ms,
          &res.times.ransac_ms);
      if (k == 0 || reg)
        res.matches = nm;
      if (reg)
      {
        ref = id;
        return;
      }
    }
  };
  track(cur);
  // A ROI registration on few inliers, or one that leaves the pose poorly
  // determined, is kept only when nothing better exists.
  const bool weakRoi = reg && isRoiMode(o.mode) && !fallback && isWeakRoiRegistration(*reg, o);
  if ((!reg || weakRoi) && isRoiMode(o.mode) && !o.strict_roi && !fallback &&
      full.features.size() > cur.features.size())
  {
    // The ROI's features did not register (or barely): the whole image's may.
    const auto roiReg = reg;
    const std::size_t roiRef = ref;
    const std::size_t roiMatches = res.matches;
    track(full);
    // Kept when the whole image does not register, or registers but leaves
    // the pose even less determined (a blurred frame's few full-image
    // inliers can be worse than a sharp ROI's).
    if (!reg || (roiReg && lessDetermined(*reg, *roiReg)))
    {
      reg = roiReg;
      ref = roiRef;
      res.matches = roiMatches;
    }
    else
    {
      fallback = true;
      cur = full;
      cur.fullImageFallback = true;
      res.trackingFeatures = cur.features.size();
    }
  }

  // Rolling shutter, second pass: the velocity this registration measured
  // since the last frame replaces the predicted one (it lags by
  // half a frame instead of one and a half), and the same matches are
  // refined again. Measured on fr1/rpy; a third pass was not better.
  if (reg && readout != 0 && I.haveStamp && frame.timestamp > I.lastStamp)
  {
    const mrpt::poses::CPose3D measured =
        (m_keyframes[ref].pose + detail::toPose(reg->T)) - lastWorld;
    const detail::TCameraRate rate = detail::cameraRate(measured, frame.timestamp - I.lastStamp);
    // The first keyframe, uncorrected so far, gets the velocity measured
    // from it to this frame (it was the last frame) and this registration
    // is refined against its corrected points.
    if (I.uncorrected && I.uncorrected->id == ref && I.lastStamp == m_keyframes[ref].timestamp)
      detail::correctKeyframe(m_keyframes[ref], *I.uncorrected, rate, readout, I.pinhole);
    I.uncorrected.reset();
    // Points and pixels only: the feature sets keep their descriptors.
    auto rebuild = [&]()
    {
      detail::updateFeatureSetPoints(full, lifted, valid, I.pinhole);
      detail::updateFeatureSetPoints(cur, lifted, fallback ? valid : chosen, I.pinhole);
    };
    detail::rectifyRollingShutter(lifted, rate, readout, I.pinhole);
    rebuild();
    if (auto again = detail::refineRegistration(m_keyframes[ref], cur, *reg, I.pinhole, o))
      reg = std::move(again);
    else
    {
      detail::rectifyRollingShutter(lifted, ratePredicted, readout, I.pinhole);
      rebuild();
    }
  }
  if (reg && o.icp_refine_sigma_m > 0 && I.icpMaps.count(ref))
  {
    // A feature registration that leaves the pose poorly determined (blur,
    // few inliers, features crowded in one region) is combined with depth
    // ICP against the same keyframe, started from it: the depth geometry
    // constrains exactly the directions the few features do not.
    const auto sg = worstSigmas(toMrptEstimate(*reg).second);
    if (!sg || sg->translation_m > o.icp_refine_sigma_m)
    {
      const auto ti = Clock::now();
      const auto ir = I.icp->align(I.icpMaps[ref], I.icp->buildMap(depth), reg->T);
      if (ir)
      {
        reg->T = detail::fuseLeft(reg->T, reg->information, ir->T, ir->information);
        reg->information += ir->information;
        res.icpRefined = true;
      }
      res.times.icp_ms += msSince(ti);
    }
  }
  if (reg)
  {
    res.method = featureMethod(o.mode, fallback);
    std::tie(res.relativePose, res.relativeInformation) = toMrptEstimate(*reg);
    res.inliers = reg->inliers;
  }
  else if (o.strict_roi && isRoiMode(o.mode))
  {
    res.method = ETrackingMethod::Lost;
    return finish();
  }
  else
  {
    bool done = false;
    if (o.icp_fallback && I.icpMaps.count(lastKf))
    {
      const auto ti = Clock::now();
      const auto curMap = I.icp->buildMap(depth);
      const auto ir = I.icp->align(I.icpMaps[lastKf], curMap, detail::fromPose(predictedRel));
      res.times.icp_ms += msSince(ti);
      if (ir)
      {
        res.method = ETrackingMethod::DepthIcp;
        std::tie(res.relativePose, res.relativeInformation) = toMrptEstimate(*ir);
        res.inliers = ir->pairs;
        done = true;
      }
    }
    if (!done)
    {
      res.method = ETrackingMethod::ConstantVelocity;
      res.relativePose = predictedRel;
      res.relativeInformation = scaledIdentity(o.constant_velocity_information_scale);
      res.inliers = 0;
    }
    ref = lastKf;
  }
  res.referenceKeyframe = ref;
  mrpt::poses::CPose3D world = m_keyframes[ref].pose + res.relativePose;
  res.pose = world;
  setVelocity(world - lastWorld);

  // Keyframe decision, on the motion since the last keyframe.
  const mrpt::poses::CPose3D sinceLast = world - m_keyframes[lastKf].pose;
  const double dist = sinceLast.translation().norm();
  const double angDeg = rotationAngle(sinceLast) * 180.0 / M_PI;
  bool makeKf =
      dist > o.keyframe_translation_m || angDeg > o.keyframe_rotation_deg || ref != lastKf;
  if (isFeatureMethod(res.method) && static_cast<int>(res.inliers) < o.keyframe_min_inliers)
    makeKf = true;

  if (!makeKf)
  {
    I.haveLast = true;
    I.lastRef = ref;
    I.lastRel = res.relativePose;
    return finish();
  }

  // New keyframe: odometry edge from the reference, plus recent keyframes.
  const auto tk = Clock::now();
  // ROI modes: the keyframe's edges come from the whole image's features it
  // stores anyway (as loop closures do); the ROI tracks the frames between.
  const bool fullEdges = isRoiMode(o.mode) && !o.strict_roi && o.keyframe_full_features &&
                         o.keyframe_full_registration && cur.features.size() < full.features.size();
  if (fullEdges && isFeatureMethod(res.method))
  {
    if (const auto r = registerSets(
            m_keyframes[ref], full, I.matcher, I.ransac, I.pinhole, o, nullptr, nullptr, nullptr))
    {
      std::tie(res.relativePose, res.relativeInformation) = toMrptEstimate(*r);
      res.inliers = r->inliers;
      world = m_keyframes[ref].pose + res.relativePose;
      res.pose = world;
      setVelocity(world - lastWorld);
    }
  }
  const TKeyframe& edgeSet = fullEdges ? full : cur;
  TKeyframeConstraint first;
  first.fromKeyframe = ref;
  first.toKeyframe = m_keyframes.size();
  first.relativePose = res.relativePose;
  first.information = res.relativeInformation;
  first.method = res.method;
  first.inliers = res.inliers;
  res.constraints.push_back(first);
  int extra = 0;
  for (std::size_t k = 0; k <= lastKf && extra < o.recent_keyframes; ++k)
  {
    const std::size_t id = lastKf - k;
    if (id == ref)
      continue;
    ++extra;
    const auto r = registerSets(
        m_keyframes[id], edgeSet, I.matcher, I.ransac, I.pinhole, o, nullptr, nullptr, nullptr);
    if (!r)
      continue;
    TKeyframeConstraint c;
    c.fromKeyframe = id;
    c.toKeyframe = first.toKeyframe;
    std::tie(c.relativePose, c.information) = toMrptEstimate(*r);
    c.method = featureMethod(o.mode, fallback);
    c.inliers = r->inliers;
    res.constraints.push_back(c);
  }
  res.times.keyframe_ms = msSince(tk);
  addKeyframe(world);
  return finish();
}
}  // namespace roislam::frontend
