/* The live view's 3-D content (CLiveScene) without a window: keyframe
 * clouds follow their keyframes when an optimisation moves them, the path
 * is the keyframes' poses composed with the frames' relative poses, a new
 * loop closure flashes for flash_s and then stays drawn, the ground truth
 * is aligned at the first frame and shown up to the current one, and the
 * view is gravity-up from the first camera. */
#include <gtest/gtest.h>
#include <mrpt/opengl/COpenGLScene.h>
#include <roislam/gui/CLiveScene.h>

#include <cmath>

using mrpt::poses::CPose3D;
using roislam::gui::CLiveScene;
using roislam::gui::TLiveFrame;

namespace
{
/** A frame `index` tracked against keyframe `ref` (world pose `refPose`),
 *  at world pose `pose`; a new keyframe `kf` when kf >= 0 (with a cloud of
 *  one point 1 m ahead of it). */
TLiveFrame frame(
    std::size_t index, const CPose3D& pose, std::size_t ref, const CPose3D& refPose, int kf = -1)
{
  TLiveFrame f;
  f.index = index;
  f.timestamp = 10.0 + 0.1 * index;
  f.method = roislam::frontend::ETrackingMethod::Features;
  f.pose = pose;
  f.referenceKeyframe = ref;
  f.relativePose = pose - refPose;
  if (kf >= 0)
  {
    f.isNewKeyframe = true;
    f.newKeyframeId = static_cast<std::size_t>(kf);
    f.cloud = roislam::gui::TKeyframeCloud{{0.f, 0.f, 1.f, 255, 0, 0}};
  }
  return f;
}

double distance(const mrpt::math::TPoint3D& a, const mrpt::math::TPoint3D& b)
{
  return (a - b).norm();
}
}  // namespace

TEST(LiveScene, CloudsFollowOptimisedKeyframesAndPathComposes)
{
  CLiveScene scene;
  mrpt::opengl::COpenGLViewport viewport;
  const CPose3D k0, k1(1, 0, 0, 0, 0, 0);
  scene.addFrame(frame(0, k0, 0, k0, 0), 0);
  scene.addFrame(frame(1, CPose3D(0.5, 0, 0, 0, 0, 0), 0, k0), 0);
  scene.addFrame(frame(2, k1, 0, k0, 1), 0);
  TLiveFrame lost;
  lost.index = 3;
  lost.timestamp = 10.3;
  scene.addFrame(lost, 0);  // no pose: not drawn
  scene.update(viewport, 0);
  ASSERT_EQ(scene.keyframeClouds(), 2u);
  ASSERT_EQ(scene.trajectory().size(), 3u);
  const auto d = scene.toDisplay();
  EXPECT_LT(distance(scene.trajectory()[1], (d + CPose3D(0.5, 0, 0, 0, 0, 0)).translation()), 1e-9);
  EXPECT_LT(distance(scene.cloudPose(1)->translation(), (d + k1).translation()), 1e-6);

  // An optimisation moves keyframe 1 by 0.2 m: its cloud and the frames
  // tracked from it move with it, keyframe 0's do not.
  const CPose3D k1b(1, 0.2, 0, 0, 0, 0);
  scene.setKeyframePoses({{0, k0}, {1, k1b}}, {}, 1);
  scene.update(viewport, 1);
  EXPECT_LT(distance(scene.cloudPose(1)->translation(), (d + k1b).translation()), 1e-6);
  EXPECT_LT(distance(scene.cloudPose(0)->translation(), (d + k0).translation()), 1e-6);
  EXPECT_LT(distance(scene.trajectory()[2], (d + k1b).translation()), 1e-9);
  EXPECT_LT(distance(scene.trajectory()[1], (d + CPose3D(0.5, 0, 0, 0, 0, 0)).translation()), 1e-9);
  // The clouds are in the viewport, named by keyframe.
  EXPECT_TRUE(viewport.getByName("live_cloud_1"));
  EXPECT_TRUE(viewport.getByName("live_trajectory"));
}

TEST(LiveScene, NewClosureFlashesThenStays)
{
  CLiveScene::TOptions o;
  o.flashS = 2.0;
  CLiveScene scene(o);
  mrpt::opengl::COpenGLViewport viewport;
  const CPose3D k0, k1(1, 0, 0, 0, 0, 0);
  scene.addFrame(frame(0, k0, 0, k0, 0), 0);
  auto f = frame(1, k1, 0, k0, 1);
  f.loops = std::vector<std::pair<std::size_t, std::size_t>>{{0, 1}};
  scene.addFrame(f, 10.0);
  scene.update(viewport, 10.5);
  EXPECT_EQ(scene.flashingClosures(10.5), 1u);
  EXPECT_EQ(scene.flashingClosures(12.5), 0u);
  // Still listed after an optimisation that kept it (its flash time kept),
  // gone when the optimisation removed it.
  scene.setKeyframePoses({{0, k0}, {1, k1}}, {{0, 1}}, 11.0);
  EXPECT_EQ(scene.flashingClosures(11.9), 1u);
  EXPECT_EQ(scene.flashingClosures(12.1), 0u);
  scene.setKeyframePoses({{0, k0}, {1, k1}}, {}, 13.0);
  EXPECT_EQ(scene.flashingClosures(13.0), 0u);
}

TEST(LiveScene, GroundTruthAlignedAtFirstFrameAndShownUpToNow)
{
  CLiveScene scene;
  // Ground truth in its own world: the estimate's path moved by 2 m and
  // turned by 90 deg, sampled every 0.05 s from before the first frame.
  const CPose3D gtWorld(2, 3, 1, M_PI / 2, 0, 0);
  roislam::io::TTrajectory gt;
  for (int i = -4; i <= 40; ++i)
  {
    const double t = 10.0 + 0.05 * i;
    gt.push_back({t, gtWorld + CPose3D(std::max(0.0, t - 10.0), 0, 0, 0, 0, 0)});
  }
  scene.setGroundTruth(gt);
  const CPose3D k0;
  scene.addFrame(frame(0, k0, 0, k0, 0), 0);
  scene.addFrame(frame(5, CPose3D(0.5, 0, 0, 0, 0, 0), 0, k0), 0);  // t = 10.5
  const auto shown = scene.groundTruthShown();
  ASSERT_FALSE(shown.empty());
  // Samples from the first frame's time to the current one only.
  EXPECT_EQ(shown.size(), 11u);  // 10.00, 10.05, ..., 10.50
  const auto d = scene.toDisplay();
  EXPECT_LT(distance(shown.front(), d.translation()), 1e-9);
  EXPECT_LT(distance(shown.back(), (d + CPose3D(0.5, 0, 0, 0, 0, 0)).translation()), 1e-9);
}

TEST(LiveScene, GravityUpFromTheFirstCameraAndFrustumAlongItsView)
{
  CLiveScene scene;
  mrpt::opengl::COpenGLViewport viewport;
  const CPose3D k0;  // optical: x right, y down, z forward
  scene.addFrame(frame(0, k0, 0, k0, 0), 0);
  scene.update(viewport, 0);
  const auto d = scene.toDisplay();
  // A point above the first camera (optical -y) is higher in the display.
  const auto above = d.composePoint(mrpt::math::TPoint3D(0, -1, 0));
  const auto origin = d.composePoint(mrpt::math::TPoint3D(0, 0, 0));
  EXPECT_NEAR(above.z - origin.z, 1.0, 1e-9);
  // The frustum's axis (+x) is the camera's view (optical +z).
  const auto marker = scene.cameraMarkerPose();
  ASSERT_TRUE(marker);
  const auto tip = marker->composePoint(mrpt::math::TPoint3D(1, 0, 0));
  const auto ahead = d.composePoint(mrpt::math::TPoint3D(0, 0, 1));
  EXPECT_LT(distance(tip, ahead), 1e-6);
  // The bounds hold the camera and its cloud point 1 m ahead.
  const auto box = scene.bounds();
  ASSERT_TRUE(box);
  for (const mrpt::math::TPoint3D& p : {origin, ahead})
  {
    EXPECT_GE(p.x, box->min.x - 1e-6);
    EXPECT_LE(p.x, box->max.x + 1e-6);
    EXPECT_GE(p.y, box->min.y - 1e-6);
    EXPECT_LE(p.y, box->max.y + 1e-6);
  }
}
