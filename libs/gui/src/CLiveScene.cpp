#include "roislam/gui/CLiveScene.h"

#include <roislam/graphslam/CGravityFrame.h>
#include <roislam/io/TumAccelerometer.h>
#include <roislam/viz/SceneBounds.h>
#include <roislam/viz/TSceneContent.h>

#include <algorithm>
#include <cmath>

namespace roislam::gui
{
namespace
{
using mrpt::math::TPoint3D;
using mrpt::poses::CPose3D;

/** The ground truth counts as known at a frame when a sample lies this
 *  close to its stamp (s); TUM's motion capture runs at 100 Hz. */
constexpr double kGroundTruthGapS = 0.05;

/** Turns the frustum's axis (+x, MRPT's convention) into the camera's
 *  optical +z, its +z into the camera's up (-y). */
CPose3D frustumInCamera()
{
  mrpt::math::CMatrixDouble33 r;
  r(0, 0) = 0, r(0, 1) = -1, r(0, 2) = 0;
  r(1, 0) = 0, r(1, 1) = 0, r(1, 2) = -1;
  r(2, 0) = 1, r(2, 1) = 0, r(2, 2) = 0;
  CPose3D p;
  p.setRotationMatrix(r);
  return p;
}

std::optional<CPose3D> nearestPose(const io::TTrajectory& t, double stamp)
{
  const auto it = std::lower_bound(
      t.begin(), t.end(), stamp,
      [](const io::TPoseStamped& p, double s) { return p.timestamp < s; });
  const io::TPoseStamped* best = nullptr;
  if (it != t.end())
    best = &*it;
  if (it != t.begin() && (!best || stamp - std::prev(it)->timestamp < best->timestamp - stamp))
    best = &*std::prev(it);
  if (!best || std::abs(best->timestamp - stamp) > kGroundTruthGapS)
    return std::nullopt;
  return best->pose;
}
}  // namespace

CLiveScene::CLiveScene() : CLiveScene(TOptions()) {}

CLiveScene::CLiveScene(const TOptions& options)
    : m_options(options),
      m_trajectory(mrpt::opengl::CSetOfLines::Create()),
      m_gtLines(mrpt::opengl::CSetOfLines::Create()),
      m_loopLines(mrpt::opengl::CSetOfLines::Create()),
      m_flashLines(mrpt::opengl::CSetOfLines::Create()),
      m_keyframeMarks(mrpt::opengl::CPointCloud::Create()),
      m_camera(mrpt::opengl::CFrustum::Create(0.03f, 0.25f, 60.f, 45.f, 2.f, true, false)),
      m_grid(mrpt::opengl::CGridPlaneXY::Create())
{
  m_trajectory->setName("live_trajectory");
  m_trajectory->setColor_u8(60, 150, 255);
  m_trajectory->setLineWidth(2.5f);
  m_gtLines->setName("live_ground_truth");
  m_gtLines->setColor_u8(60, 220, 60);
  m_gtLines->setLineWidth(2.0f);
  m_loopLines->setName("live_loops");
  m_loopLines->setColor_u8(255, 70, 70);
  m_loopLines->setLineWidth(1.5f);
  m_flashLines->setName("live_loops_new");
  m_flashLines->setColor_u8(255, 240, 0);
  m_flashLines->setLineWidth(6.0f);
  m_keyframeMarks->setName("live_keyframes");
  m_keyframeMarks->setColor_u8(60, 150, 255);
  m_keyframeMarks->setPointSize(7.0f);
  m_camera->setName("live_camera");
  m_camera->setColor_u8(255, 0, 255);
  m_camera->setVisibility(false);
  m_grid->setName("live_grid");
  m_grid->setColor_u8(110, 110, 110);
  m_grid->setVisibility(false);
}

void CLiveScene::setGroundTruth(io::TTrajectory groundTruth)
{
  m_groundTruth = std::move(groundTruth);
  m_gtToWorld.reset();
  if (m_started && !m_frames.empty())
  {
    // Aligned at the first tracked frame, as startDisplayFrame() does.
    const auto first = framePose(m_frames.front());
    const auto gt0 = nearestPose(m_groundTruth, m_frames.front().timestamp);
    if (first && gt0)
      m_gtToWorld = *first + (-*gt0);
  }
  m_posesDirty = true;
}

void CLiveScene::startDisplayFrame(const TLiveFrame& frame)
{
  m_started = true;
  m_toDisplay = graphslam::CGravityFrame::choose(
                    {{frame.timestamp, *frame.pose}}, std::nullopt, io::TAccelerometerLog{})
                    .toDisplay;
  if (const auto gt0 = nearestPose(m_groundTruth, frame.timestamp))
    m_gtToWorld = *frame.pose + (-*gt0);
}

void CLiveScene::addFrame(const TLiveFrame& frame, double now)
{
  m_lastStamp = frame.timestamp;
  if (frame.loops)
    setLoops(*frame.loops, now);
  if (!frame.pose)
    return;  // Lost: no pose to draw
  if (!m_started)
    startDisplayFrame(frame);
  m_frames.push_back(
      {frame.timestamp, frame.referenceKeyframe, frame.relativePose, frame.isNewKeyframe,
       frame.newKeyframeId});
  m_posesDirty = true;
  if (!frame.isNewKeyframe)
    return;
  // An optimisation inside the same step may already have given the node.
  m_keyframePoses.emplace(frame.newKeyframeId, *frame.pose);
  if (!frame.cloud)
    return;
  auto cloud = mrpt::opengl::CPointCloudColoured::Create();
  cloud->setName("live_cloud_" + std::to_string(frame.newKeyframeId));
  cloud->reserve(frame.cloud->size());
  auto& sample = m_framing[frame.newKeyframeId];
  const std::size_t step = std::max<std::size_t>(
      1, frame.cloud->size() / std::max<std::size_t>(1, m_options.framingPointsPerKeyframe));
  for (std::size_t i = 0; i < frame.cloud->size(); ++i)
  {
    cloud->insertPoint((*frame.cloud)[i]);
    if (i % step == 0)
      sample.push_back((*frame.cloud)[i].pt);
  }
  cloud->setPointSize(m_options.pointSize);
  m_clouds[frame.newKeyframeId] = cloud;
  m_newClouds.push_back(cloud);
}

void CLiveScene::setKeyframePoses(
    const std::map<std::size_t, CPose3D>& poses,
    const std::vector<std::pair<std::size_t, std::size_t>>& loops, double now)
{
  for (const auto& [id, pose] : poses)
    m_keyframePoses[id] = pose;
  setLoops(loops, now);
  m_posesDirty = true;
}

void CLiveScene::setLoops(const std::vector<std::pair<std::size_t, std::size_t>>& loops, double now)
{
  std::vector<TLoop> next;
  next.reserve(loops.size());
  for (const auto& [from, to] : loops)
  {
    const auto old = std::find_if(
        m_loops.begin(), m_loops.end(),
        [&](const TLoop& l) { return l.from == from && l.to == to; });
    next.push_back({from, to, old != m_loops.end() ? old->acceptedAt : now});
  }
  m_loops = std::move(next);
}

std::optional<CPose3D> CLiveScene::framePose(const TFramePose& f) const
{
  const auto it = m_keyframePoses.find(f.isKeyframe ? f.keyframe : f.reference);
  if (it == m_keyframePoses.end())
    return std::nullopt;
  return f.isKeyframe ? it->second : it->second + f.relative;
}

std::optional<TPoint3D> CLiveScene::keyframePosition(std::size_t id) const
{
  const auto it = m_keyframePoses.find(id);
  if (it == m_keyframePoses.end())
    return std::nullopt;
  return (m_toDisplay + it->second).translation();
}

std::vector<TPoint3D> CLiveScene::trajectory() const
{
  std::vector<TPoint3D> path;
  path.reserve(m_frames.size());
  for (const auto& f : m_frames)
    if (const auto p = framePose(f))
      path.push_back((m_toDisplay + *p).translation());
  return path;
}

std::vector<TPoint3D> CLiveScene::groundTruthShown() const
{
  std::vector<TPoint3D> path;
  if (!m_gtToWorld)
    return path;
  const CPose3D toDisplay = m_toDisplay + *m_gtToWorld;
  for (const auto& p : m_groundTruth)
  {
    if (p.timestamp > m_lastStamp + 1e-6)
      break;
    if (!m_frames.empty() && p.timestamp < m_frames.front().timestamp - 1e-6)
      continue;
    path.push_back((toDisplay + p.pose).translation());
  }
  return path;
}

void CLiveScene::rebuildPaths()
{
  const auto addStrip = [](mrpt::opengl::CSetOfLines& lines, const std::vector<TPoint3D>& pts)
  {
    lines.clear();
    lines.reserve(pts.size());
    for (std::size_t i = 1; i < pts.size(); ++i)
      lines.appendLine(pts[i - 1], pts[i]);
  };
  const auto path = trajectory();
  addStrip(*m_trajectory, path);
  addStrip(*m_gtLines, groundTruthShown());
  m_keyframeMarks->clear();
  for (const auto& [id, pose] : m_keyframePoses)
  {
    const auto t = (m_toDisplay + pose).translation();
    m_keyframeMarks->insertPoint(t.x, t.y, t.z);
  }
  if (!m_frames.empty())
    if (const auto p = framePose(m_frames.back()))
    {
      m_camera->setPose(m_toDisplay + *p + frustumInCamera());
      m_camera->setVisibility(true);
    }
}

void CLiveScene::rebuildLoops(double now)
{
  m_loopLines->clear();
  m_flashLines->clear();
  for (const auto& l : m_loops)
  {
    const auto a = keyframePosition(l.from), b = keyframePosition(l.to);
    if (!a || !b)
      continue;
    m_loopLines->appendLine(*a, *b);
    if (now - l.acceptedAt < m_options.flashS)
      m_flashLines->appendLine(*a, *b);
  }
}

void CLiveScene::rebuildGrid()
{
  const auto box = bounds();
  if (!box)
    return;
  const auto size = box->max - box->min;
  const double spacing = viz::niceGridSpacing(std::max(size.x, size.y));
  const auto lo = [spacing](double v) { return std::floor(v / spacing) * spacing; };
  const auto hi = [spacing](double v) { return std::ceil(v / spacing) * spacing; };
  m_grid->setPlaneLimits(lo(box->min.x), hi(box->max.x), lo(box->min.y), hi(box->max.y));
  m_grid->setPlaneZcoord(static_cast<float>(box->min.z));
  m_grid->setGridFrequency(static_cast<float>(spacing));
  m_grid->setVisibility(true);
}

void CLiveScene::update(mrpt::opengl::COpenGLViewport& viewport, double now)
{
  if (!m_attached)
  {
    for (const auto& o : std::vector<mrpt::opengl::CRenderizable::Ptr>{
             m_grid, m_gtLines, m_trajectory, m_loopLines, m_flashLines, m_keyframeMarks, m_camera})
      viewport.insert(o);
    m_attached = true;
  }
  for (const auto& c : m_newClouds)
    viewport.insert(c);
  m_newClouds.clear();
  if (m_posesDirty)
  {
    for (const auto& [id, cloud] : m_clouds)
    {
      const auto it = m_keyframePoses.find(id);
      if (it != m_keyframePoses.end())
        cloud->setPose(m_toDisplay + it->second);
    }
    rebuildPaths();
    rebuildGrid();
    m_posesDirty = false;
  }
  rebuildLoops(now);
}

std::optional<mrpt::math::TBoundingBox> CLiveScene::bounds() const
{
  viz::TSceneContent content;
  for (const auto& [id, sample] : m_framing)
  {
    const auto it = m_keyframePoses.find(id);
    if (it == m_keyframePoses.end())
      continue;
    const CPose3D pose = m_toDisplay + it->second;
    for (const auto& p : sample)
    {
      double x, y, z;
      pose.composePoint(p.x, p.y, p.z, x, y, z);
      content.cloud.insertPoint(
          static_cast<float>(x), static_cast<float>(y), static_cast<float>(z));
    }
  }
  content.trajectory = trajectory();
  content.groundTruth = groundTruthShown();
  return viz::robustBounds(content, 0.03);
}

mrpt::math::TVector3D CLiveScene::lookDirection() const
{
  mrpt::math::TVector3D sum(0, 0, 0);
  for (const auto& [id, pose] : m_keyframePoses)
  {
    const auto r = (m_toDisplay + pose).getRotationMatrix();
    sum += mrpt::math::TVector3D(r(0, 2), r(1, 2), r(2, 2));
  }
  return sum;
}

std::size_t CLiveScene::flashingClosures(double now) const
{
  return static_cast<std::size_t>(std::count_if(
      m_loops.begin(), m_loops.end(),
      [&](const TLoop& l) { return now - l.acceptedAt < m_options.flashS; }));
}

std::optional<CPose3D> CLiveScene::cloudPose(std::size_t keyframe) const
{
  const auto it = m_clouds.find(keyframe);
  if (it == m_clouds.end())
    return std::nullopt;
  return CPose3D(it->second->getPose());
}

std::optional<CPose3D> CLiveScene::cameraMarkerPose() const
{
  if (!m_camera->isVisible())
    return std::nullopt;
  return CPose3D(m_camera->getPose());
}
}  // namespace roislam::gui
