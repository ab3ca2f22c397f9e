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
  const cv::Size size = grey.size();
  const auto roi = m_detector.detect(grey);
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
  const features::TFeatureSet roiFeatures = all.subset(roi->box);
  r.roiFeatures = static_cast<int>(roiFeatures.size());

  const auto roiPoints = featurePoints(
      roiFeatures.keypoints, frame.depth, frame.camera, m_options.tracker.min_depth,
      m_options.tracker.max_depth);
  const TFeatureDepth depth = depthStatistics(roiPoints);
  r.depthValid = depth.valid;
  r.depthMean = depth.mean;
  r.depthMedian = depth.median;
  r.roiPosition = depth.position;

  // Confirmation: the current ROI is re-found in the previous frame.
  if (m_options.tracker.confirm)
  {
    if (!m_previous || roiFeatures.empty())
      return finish();
    const auto matches = m_matcher.match(roiFeatures, *m_previous);
    r.matches = static_cast<int>(matches.size());
    const auto located = m_locator.locate(roiFeatures, roi->box, *m_previous, size, matches);
    if (!located)
    {
      r.falseMatches = r.matches;  // nothing located: no match is trusted
      return finish();
    }
    r.falseMatches = located->falseMatches;
  }
  if (roiFeatures.empty())
    return finish();
  r.secondsConfirm += lap();
  stage = &r.secondsQuery;

  std::optional<mrpt::math::TPoint3D> world;
  if (cameraPose && depth.position)
    world = cameraPose->composePoint(*depth.position);

  const auto q = m_database.query(roiFeatures, roi->box, size, roiPoints, world);
  r.candidates = q.candidates;
  r.status = ERoiStatus::Landmark;

  TLandmarkSighting sighting;
  sighting.frame = frame.index;
  sighting.timestamp = frame.timestamp;
  sighting.box = roi->box;
  sighting.hasPosition = depth.position.has_value();
  if (depth.position)
    sighting.position = *depth.position;

  // Where the recalled landmark's stored point is now: the 3-D alignment of
  // the inliers' first-sight points with their current points maps it here;
  // without usable depth, the features inside the located box.
  std::optional<mrpt::math::TPoint3D> recalledAt;
  if (q.landmarkId)
  {
    const CLandmark& lm = m_database.landmark(*q.landmarkId);
    if (q.rigid && lm.hasPositionCamera)
      recalledAt = q.rigid->pose.composePoint(lm.positionCamera);
    else
      recalledAt =
          featureDepth(
              all.subset(q.locatedBox & cv::Rect(cv::Point(0, 0), size)).keypoints, frame.depth,
              frame.camera, m_options.tracker.min_depth, m_options.tracker.max_depth)
              .position;
  }
  // Optional: a ROI whose own position is far from the recalled landmark's
  // covers a different extent of the scene; treat it as a new region.
  const double maxJump = m_options.tracker.max_position_jump;
  const bool jumped = maxJump > 0 && recalledAt && depth.position &&
                      (*recalledAt - *depth.position).norm() > maxJump;

  if (q.landmarkId && !jumped)
  {
    r.landmarkId = *q.landmarkId;
    r.recallInliers = q.inliers;
    r.landmarkBox = q.locatedBox & cv::Rect(cv::Point(0, 0), size);
    r.landmarkPosition = recalledAt;
    if (q.rigid)
    {
      r.rigidInliers = q.rigid->inliers;
      r.rigidRms = q.rigid->rms;
    }
    sighting.inliers = q.inliers;
    m_database.addSighting(*q.landmarkId, sighting);
    return finish();
  }

  CLandmark lm;
  lm.features = roiFeatures;
  lm.featurePoints = roiPoints;
  lm.box = roi->box;
  lm.imageSize = size;
  lm.patch = frame.rgb.empty() ? grey(roi->box).clone() : frame.rgb(roi->box).clone();
  if (depth.position)
  {
    lm.positionCamera = *depth.position;
    lm.hasPositionCamera = true;
  }
  if (world)
  {
    lm.positionWorld = *world;
    lm.hasPositionWorld = true;
  }
  lm.sightings.push_back(sighting);
  r.landmarkBox = roi->box;
  r.landmarkPosition = depth.position;
  r.landmarkId = m_database.add(std::move(lm));
  r.newLandmark = true;
  return finish();
}
}  // namespace roislam::landmarks
