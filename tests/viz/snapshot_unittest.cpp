/* The viz library: a SLAM scene that saves as a .3Dscene and loads back with
 * the same objects, and a headless (EGL) snapshot that a user reads at a
 * glance: the map fills both panels, the floor of a z-up room is at the
 * bottom of the 3-D view, a ceiling does not hide the top view, and the
 * trajectories and legend are drawn. */
#include <mrpt/img/CImage.h>
#include <mrpt/opengl/COpenGLScene.h>
#include <roislam/testing/TestData.h>
#include <roislam/viz/CSlamSceneBuilder.h>
#include <roislam/viz/CSnapshotRenderer.h>
#include <roislam/viz/SceneBounds.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <opencv2/core.hpp>

using roislam::viz::CSnapshotRenderer;
using roislam::viz::TSceneContent;

namespace
{
// Colours of the test room's surfaces (RGB in [0,1]).
constexpr float kFloor[3] = {0.9f, 0.1f, 0.1f};    // red
constexpr float kWall[3] = {0.5f, 0.5f, 0.5f};     // grey
constexpr float kCeiling[3] = {0.1f, 0.1f, 0.9f};  // blue

void addRect(
    TSceneContent& c, const mrpt::math::TPoint3D& o, const mrpt::math::TVector3D& u,
    const mrpt::math::TVector3D& v, const float* rgb)
{
  const double step = 0.02;
  const int nu = static_cast<int>(u.norm() / step), nv = static_cast<int>(v.norm() / step);
  for (int i = 0; i <= nu; ++i)
    for (int j = 0; j <= nv; ++j)
    {
      const auto p = o + u * (double(i) / nu) + v * (double(j) / nv);
      c.cloud.insertPointRGB(
          static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z), rgb[0], rgb[1],
          rgb[2]);
    }
}

/** A z-up room 3 x 2.5 m (floor at z = 0, walls 2 m high on three sides), a
 *  camera loop at 1.4 m looking towards +x, optionally a ceiling. */
TSceneContent room(bool ceiling = false)
{
  TSceneContent c;
  addRect(c, {0, -1.25, 0}, {3, 0, 0}, {0, 2.5, 0}, kFloor);
  addRect(c, {3, -1.25, 0}, {0, 2.5, 0}, {0, 0, 2}, kWall);
  addRect(c, {0, -1.25, 0}, {3, 0, 0}, {0, 0, 2}, kWall);
  addRect(c, {0, 1.25, 0}, {3, 0, 0}, {0, 0, 2}, kWall);
  if (ceiling)
    addRect(c, {0, -1.25, 2.2}, {3, 0, 0}, {0, 2.5, 0}, kCeiling);
  for (int k = 0; k <= 36; ++k)
  {
    const double a = k * 10.0 * M_PI / 180.0;
    c.trajectory.emplace_back(0.8 + 0.3 * std::cos(a), 0.3 * std::sin(a), 1.4);
    c.groundTruth.emplace_back(0.8 + 0.31 * std::cos(a), 0.31 * std::sin(a), 1.41);
    if (k % 6 == 0)
      c.keyframes.push_back(c.trajectory.back());
  }
  c.lookDirection = {1, 0, -0.3};
  c.legend = {"test room", "mode roi_big, orb"};
  return c;
}

cv::Mat panel(const mrpt::img::CImage& img, const CSnapshotRenderer& r, int k)
{
  const cv::Mat m = img.asCvMat<cv::Mat>(mrpt::img::SHALLOW_COPY);
  return m(cv::Rect(
      static_cast<int>(k * r.panelWidth()), static_cast<int>(r.headerHeight()),
      static_cast<int>(r.panelWidth()), static_cast<int>(r.panelHeight())));
}

/** Rows of the pixels close to an RGB colour in [0,1]. */
std::vector<int> rowsOf(const cv::Mat& m, const float* rgb)
{
  std::vector<int> rows;
  for (int r = 0; r < m.rows; ++r)
    for (int c = 0; c < m.cols; ++c)
    {
      const auto px = m.at<cv::Vec3b>(r, c);  // BGR
      if (std::abs(px[2] - 255 * rgb[0]) < 40 && std::abs(px[1] - 255 * rgb[1]) < 40 &&
          std::abs(px[0] - 255 * rgb[2]) < 40)
        rows.push_back(r);
    }
  return rows;
}

int median(std::vector<int> v)
{
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

double nonBackgroundFraction(const cv::Mat& m)
{
  int n = 0;
  for (int r = 0; r < m.rows; ++r)
    for (int c = 0; c < m.cols; ++c)
    {
      const auto px = m.at<cv::Vec3b>(r, c);
      n += (px[0] < 245 || px[1] < 245 || px[2] < 245);
    }
  return static_cast<double>(n) / (m.rows * m.cols);
}

CSnapshotRenderer::TOptions small(bool overlays = true)
{
  CSnapshotRenderer::TOptions o;
  o.width = 800;
  o.height = 380;
  o.overlays = overlays;
  return o;
}
}  // namespace

TEST(Snapshot, BuildsSceneWithNamedObjects)
{
  const auto scene = roislam::viz::CSlamSceneBuilder().build(room());
  for (const char* name : {"map_cloud", "trajectory", "ground_truth", "keyframes", "grid"})
    EXPECT_TRUE(scene->getByName(name)) << name;
  // Empty content gives an empty scene (no grid without extent).
  const auto empty = roislam::viz::CSlamSceneBuilder().build(TSceneContent());
  EXPECT_FALSE(empty->getByName("trajectory"));
  EXPECT_FALSE(empty->getByName("grid"));
  // The map alone (the snapshot draws the lines itself).
  roislam::viz::CSlamSceneBuilder::TOptions o;
  o.showTrajectories = false;
  const auto mapOnly = roislam::viz::CSlamSceneBuilder(o).build(room());
  EXPECT_TRUE(mapOnly->getByName("map_cloud"));
  EXPECT_FALSE(mapOnly->getByName("trajectory"));
  EXPECT_FALSE(mapOnly->getByName("keyframes"));
}

TEST(Snapshot, GridSpacingIsRoundAndRobustBoundsIgnoreStrayPoints)
{
  EXPECT_DOUBLE_EQ(roislam::viz::niceGridSpacing(3.0), 0.5);
  EXPECT_DOUBLE_EQ(roislam::viz::niceGridSpacing(1.2), 0.2);
  EXPECT_DOUBLE_EQ(roislam::viz::niceGridSpacing(40), 10);
  auto c = room();
  const auto clean = roislam::viz::robustBounds(c);
  for (int k = 0; k < 20; ++k)
    c.cloud.insertPointRGB(50.0f + k, -40.0f, 30.0f, 0, 0, 0);
  const auto stray = roislam::viz::robustBounds(c);
  ASSERT_TRUE(clean && stray);
  EXPECT_LT((stray->max - clean->max).norm(), 0.1);
  EXPECT_FALSE(roislam::viz::robustBounds(TSceneContent()));
}

TEST(Snapshot, SceneFileRoundTrip)
{
  const std::string dir = roislam::testing::makeTempDir("viz_scene");
  const std::string file = dir + "/scene.3Dscene";
  const auto scene = roislam::viz::CSlamSceneBuilder().build(room());
  roislam::viz::CSlamSceneBuilder::save(*scene, file);
  ASSERT_TRUE(std::filesystem::exists(file));
  EXPECT_FALSE(std::filesystem::exists(file + ".tmp"));
  mrpt::opengl::COpenGLScene loaded;
  ASSERT_TRUE(loaded.loadFromFile(file));
  EXPECT_TRUE(loaded.getByName("trajectory"));
  EXPECT_TRUE(loaded.getByName("map_cloud"));
  std::filesystem::remove_all(dir);
}

TEST(Snapshot, SaveToUnwritablePathThrows)
{
  const auto scene = roislam::viz::CSlamSceneBuilder().build(room());
  EXPECT_THROW(
      roislam::viz::CSlamSceneBuilder::save(*scene, "/nonexistent_dir_xyz/scene.3Dscene"),
      std::runtime_error);
  EXPECT_THROW(
      CSnapshotRenderer(small()).renderToFile(room(), "/nonexistent_dir_xyz/s.png"),
      std::runtime_error);
}

TEST(Snapshot, MapFillsBothPanelsEvenWithStrayPoints)
{
  auto c = room();
  for (int k = 0; k < 20; ++k)  // far depth outliers must not shrink the map
    c.cloud.insertPointRGB(30.0f + k, 25.0f, -10.0f, 0, 0, 0);
  const CSnapshotRenderer r(small(false));
  const auto img = r.render(c);
  ASSERT_EQ(img.getWidth(), 800u);
  ASSERT_EQ(img.getHeight(), 380u);
  for (int k = 0; k < 2; ++k)
  {
    const double f = nonBackgroundFraction(panel(img, r, k));
    EXPECT_GT(f, 0.4) << "panel " << k;
    std::printf("panel %d: map covers %.0f %% of the pixels\n", k, 100 * f);
  }
  // Every camera position projects inside its panel, within the margin.
  for (const auto& v : r.views(c))
    for (const auto& p : c.trajectory)
    {
      const auto px = v.project(p);
      ASSERT_TRUE(px);
      EXPECT_GT(px->x, 0.03 * v.camera.ncols);
      EXPECT_LT(px->x, 0.97 * v.camera.ncols);
      EXPECT_GT(px->y, 0.03 * v.camera.nrows);
      EXPECT_LT(px->y, 0.97 * v.camera.nrows);
    }
}

TEST(Snapshot, FloorAtTheBottomOfTheThreeDView)
{
  const CSnapshotRenderer r(small(false));
  const auto img = r.render(room());
  const cv::Mat view = panel(img, r, 0);
  const auto floor = rowsOf(view, kFloor), wall = rowsOf(view, kWall);
  ASSERT_GT(floor.size(), 2000u);
  ASSERT_GT(wall.size(), 2000u);
  EXPECT_GT(median(floor), median(wall));
  EXPECT_GT(median(floor), view.rows / 2);
}

TEST(Snapshot, CeilingAboveTheCamerasDoesNotHideTheTopView)
{
  const CSnapshotRenderer r(small(false));
  const auto img = r.render(room(true));
  const cv::Mat top = panel(img, r, 1);
  EXPECT_GT(rowsOf(top, kFloor).size(), 0.3 * top.rows * top.cols);
  EXPECT_LT(rowsOf(top, kCeiling).size(), 0.01 * top.rows * top.cols);
  // The 3-D view keeps it.
  EXPECT_GT(rowsOf(panel(img, r, 0), kCeiling).size(), 1000u);
}

TEST(Snapshot, TrajectoriesKeyframesAndLegendAreDrawn)
{
  const std::string dir = roislam::testing::makeTempDir("viz_snapshot");
  const std::string file = dir + "/snapshot.png";
  const CSnapshotRenderer r(small());
  r.renderToFile(room(), file);
  mrpt::img::CImage img;
  ASSERT_TRUE(img.loadFromFile(file));
  const float estimate[3] = {0, 60 / 255.f, 220 / 255.f}, groundTruth[3] = {0, 160 / 255.f, 0};
  const float keyframe[3] = {0, 30 / 255.f, 120 / 255.f};
  for (int k = 0; k < 2; ++k)
  {
    const cv::Mat p = panel(img, r, k);
    EXPECT_GT(rowsOf(p, estimate).size(), 100u) << "panel " << k;
    EXPECT_GT(rowsOf(p, groundTruth).size(), 100u) << "panel " << k;
    EXPECT_GT(rowsOf(p, keyframe).size(), 20u) << "panel " << k;
  }
  const cv::Mat m = img.asCvMat<cv::Mat>(mrpt::img::SHALLOW_COPY);
  const float text[3] = {40 / 255.f, 40 / 255.f, 40 / 255.f};
  EXPECT_GT(
      rowsOf(m(cv::Rect(0, 0, m.cols, static_cast<int>(r.headerHeight()))), text).size(), 100u);
  std::filesystem::remove_all(dir);
}

TEST(Snapshot, EmptyContentRendersTheBackground)
{
  const CSnapshotRenderer r(small());
  EXPECT_TRUE(r.views(TSceneContent()).empty());
  const auto img = r.render(TSceneContent());
  EXPECT_EQ(nonBackgroundFraction(img.asCvMat<cv::Mat>(mrpt::img::SHALLOW_COPY)), 0.0);
}
