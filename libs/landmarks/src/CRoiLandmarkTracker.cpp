#include "roislam/landmarks/CRoiLandmarkTracker.h"

#include <chrono>
#include <ctime>
#include <limits>

#include "roislam/landmarks/FeatureGeometry.h"

namespace roislam::landmarks
{
std::string TFrameResult::statusText() const
{
  switch (status)
  {
    case ERoiStatus::NoRoi:
      return "NaN";
    case ERoiStatus::NotConfirmed:
      return "no new ROI";
    case ERoiStatus::Landmark:
      return "landmark " + std::to_string(landmarkId);
  }
  return "NaN";
}

CRoiLandmarkTracker::CRoiLandmarkTracker(const TPipelineOptions& options)
    : m_options(options),
      m_detector(options.roi),
      m_extractor(options.features),
      m_matcher(options.matcher),
      m_locator(options.locator),
      m_database(options.database, options.matcher, options.locator)
{
}

void CRoiLandmarkTracker::resetSequence()
{
  m_previous.reset();
}

namespace
{
double threadCpuSeconds()
{
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}
}  // namespace

TFrameResult CRoiLandmarkTracker::process(
    const io::TRGBDFrame& frame, const std::optional<mrpt::poses::CPose3D>& cameraPose)
{
  const auto t0 = std::chrono::steady_clock::now();
  const double cpu0 = threadCpuSeconds();
  auto lap = [last = t0]() mutable
  {
    const auto now = std::chrono::steady_clock::now();
    const double dt = std::chrono::duration<double>(now - last).count();
    last = now;
    return dt;
  };
  TFrameResult r;
  r.frame = frame.index;
  r.timestamp = frame.timestamp;
  r.depthMean = r.depthMedian = r.rigidRms = std::numeric_limits<double>::quiet_NaN();

  const cv::Mat grey = frame.grey();
  const auto detection = m_detector.detectDetailed(grey, frame.rgb);
  const auto& roi = detection.roi;
  r.rejectedByHue = detection.rejectedByHue();
  r.secondsRoi = lap();
  features::TFeatureSet all = m_extractor.extract(grey);
  r.secondsFeatures = lap();
  r.features = static_cast<int>(all.size());
  double* stage = &r.secondsConfirm;  // the stage running now

  auto finish = [&]()
  {
    *stage += lap();
    m_previous = std::move(all);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.cpuSeconds = threadCpuSeconds() - cpu0;
    return r;
  };

  if (!roi)
    return finish();
  r.roi = roi->box;
  r.status = ERoiStatus::NotConfirmed;
  const TRegion region = makeRegion(frame, grey, roi->box, all, cameraPose);
  const TFeatureDepth depth = depthStatistics(region.points);
  r.roiFeatures = static_cast<int>(region.features.size());
  r.depthValid = depth.valid;
  r.depthMean = depth.mean;
  r.depthMedian = depth.median;
  r.roiPosition = region.position;

  if (m_options.tracker.confirm && !confirm(region, r))
    return finish();
  if (region.features.empty())
    return finish();
  r.secondsConfirm += lap();
  stage = &r.secondsQuery;
  identify(region, r);
  return finish();
}

TRegion CRoiLandmarkTracker::makeRegion(
    const io::TRGBDFrame& frame, const cv::Mat& grey, const cv::Rect& box,
    const features::TFeatureSet& all, const std::optional<mrpt::poses::CPose3D>& cameraPose) const
{
  TRegion region;
  region.frame = frame.index;
  region.timestamp = frame.timestamp;
  region.box = box;
  region.imageSize = grey.size();
  region.camera = frame.camera;
  region.features = all.subset(box);
  region.points = featurePoints(
      region.features.keypoints, frame.depth, frame.camera, m_options.tracker.min_depth,
      m_options.tracker.max_depth);
  region.position = depthStatistics(region.points).position;
  if (cameraPose && region.position)
    region.worldPosition = cameraPose->composePoint(*region.position);
  region.patch = frame.rgb.empty() ? grey(box) : frame.rgb(box);
  region.frameFeatures = &all;
  region.depth = &frame.depth;
  return region;
}

bool CRoiLandmarkTracker::confirm(const TRegion& region, TFrameResult& r) const
{
  // The current ROI is re-found in the previous frame.
  if (!m_previous || region.features.empty())
    return false;
  const auto matches = m_matcher.match(region.features, *m_previous);
  r.matches = static_cast<int>(matches.size());
  const auto located =
      m_locator.locate(region.features, region.box, *m_previous, region.imageSize, matches);
  if (!located)
  {
    r.falseMatches = r.matches;  // nothing located: no match is trusted
    return false;
  }
  r.falseMatches = located->falseMatches;
  return true;
}

void CRoiLandmarkTracker::identify(const TRegion& region, TFrameResult& r)
{
  const auto q = m_database.query(
      region.features, region.box, region.imageSize, region.points, region.worldPosition);
  r.candidates = q.candidates;
  r.status = ERoiStatus::Landmark;

  TLandmarkSighting sighting;
  sighting.frame = region.frame;
  sighting.timestamp = region.timestamp;
  sighting.box = region.box;
  sighting.hasPosition = region.position.has_value();
  if (region.position)
    sighting.position = *region.position;

  const auto recalledAt = q.landmarkId ? recalledPosition(region, q) : std::nullopt;
  // Optional: a ROI whose own position is far from the recalled landmark's
  // covers a different extent of the scene; treat it as a new region.
  const double maxJump = m_options.tracker.max_position_jump;
  const bool jumped = maxJump > 0 && recalledAt && region.position &&
                      (*recalledAt - *region.position).norm() > maxJump;
  if (q.landmarkId && !jumped)
  {
    r.landmarkId = *q.landmarkId;
    r.recallInliers = q.inliers;
    r.landmarkBox = q.locatedBox & cv::Rect(cv::Point(0, 0), region.imageSize);
    r.landmarkPosition = recalledAt;
    if (q.rigid)
    {
      r.rigidInliers = q.rigid->inliers;
      r.rigidRms = q.rigid->rms;
    }
    sighting.inliers = q.inliers;
    m_database.addSighting(*q.landmarkId, sighting);
    return;
  }
  CLandmark lm;
  lm.features = region.features;
  lm.featurePoints = region.points;
  lm.box = region.box;
  lm.imageSize = region.imageSize;
  lm.patch = region.patch.clone();
  if (region.position)
  {
    lm.positionCamera = *region.position;
    lm.hasPositionCamera = true;
  }
  if (region.worldPosition)
  {
    lm.positionWorld = *region.worldPosition;
    lm.hasPositionWorld = true;
  }
  lm.sightings.push_back(sighting);
  r.landmarkBox = region.box;
  r.landmarkPosition = region.position;
  r.landmarkId = m_database.add(std::move(lm));
  r.newLandmark = true;
}

std::optional<mrpt::math::TPoint3D> CRoiLandmarkTracker::recalledPosition(
    const TRegion& region, const CLandmarkDatabase::TQueryResult& q) const
{
  // Where the recalled landmark's stored point is now: the 3-D alignment of
  // the inliers' first-sight points with their current points maps it here;
  // without usable depth, the features inside the located box.
  const CLandmark& lm = m_database.landmark(*q.landmarkId);
  if (q.rigid && lm.hasPositionCamera)
    return q.rigid->pose.composePoint(lm.positionCamera);
  if (!region.frameFeatures || !region.depth)
    return std::nullopt;
  const cv::Rect inside = q.locatedBox & cv::Rect(cv::Point(0, 0), region.imageSize);
  return featureDepth(
             region.frameFeatures->subset(inside).keypoints, *region.depth, region.camera,
             m_options.tracker.min_depth, m_options.tracker.max_depth)
      .position;
}
}  // namespace roislam::landmarks
