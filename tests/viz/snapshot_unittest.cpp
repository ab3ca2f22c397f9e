/* The viz library renders a SLAM scene headless (EGL) to a non-empty PNG and
 * saves a .3Dscene that loads back with the same objects. */
#include <mrpt/img/CImage.h>
#include <mrpt/opengl/COpenGLScene.h>
#include <roislam/testing/TestData.h>
#include <roislam/viz/CSlamSceneBuilder.h>
#include <roislam/viz/CSnapshotRenderer.h>

#include <cmath>
#include <filesystem>
#include <opencv2/core.hpp>

namespace
{
roislam::viz::TSceneContent makeContent()
{
  roislam::viz::TSceneContent c;
  // A red wall of points and a circular trajectory in front of it.
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j)
      c.cloud.insertPointRGB(0.05f * i - 1.0f, 2.0f, 0.05f * j - 1.0f, 0.9f, 0.1f, 0.1f);
  for (int k = 0; k <= 36; ++k)
  {
    const double a = k * 10.0 * M_PI / 180.0;
    c.trajectory.emplace_back(0.5 * std::cos(a), 0.5 * std::sin(a), 0);
    c.groundTruth.emplace_back(0.52 * std::cos(a), 0.52 * std::sin(a), 0.01);
  }
  return c;
}
}  // namespace

TEST(Snapshot, BuildsSceneWithNamedObjects)
{
  const auto scene = roislam::viz::CSlamSceneBuilder().build(makeContent());
  EXPECT_TRUE(scene->getByName("map_cloud"));
  EXPECT_TRUE(scene->getByName("trajectory"));
  EXPECT_TRUE(scene->getByName("ground_truth"));
  // Empty content gives an empty scene (no grid without extent).
  const auto empty = roislam::viz::CSlamSceneBuilder().build(roislam::viz::TSceneContent());
  EXPECT_FALSE(empty->getByName("trajectory"));
  EXPECT_FALSE(empty->getByName("grid"));
}

TEST(Snapshot, SceneFileRoundTrip)
{
  const std::string dir = roislam::testing::makeTempDir("viz_scene");
  const std::string file = dir + "/scene.3Dscene";
  const auto scene = roislam::viz::CSlamSceneBuilder().build(makeContent());
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
  const auto scene = roislam::viz::CSlamSceneBuilder().build(makeContent());
  EXPECT_THROW(
      roislam::viz::CSlamSceneBuilder::save(*scene, "/nonexistent_dir_xyz/scene.3Dscene"),
      std::runtime_error);
}

TEST(Snapshot, RendersNonEmptyPngHeadless)
{
  const std::string dir = roislam::testing::makeTempDir("viz_snapshot");
  const std::string file = dir + "/snapshot.png";
  roislam::viz::CSnapshotRenderer::TOptions opts;
  opts.width = 320;
  opts.height = 240;
  opts.topView = false;
  roislam::viz::CSnapshotRenderer(opts).renderToFile(makeContent(), file);
  ASSERT_TRUE(std::filesystem::exists(file));
  EXPECT_GT(std::filesystem::file_size(file), 100u);

  mrpt::img::CImage img;
  ASSERT_TRUE(img.loadFromFile(file));
  ASSERT_EQ(img.getWidth(), 320u);
  ASSERT_EQ(img.getHeight(), 240u);
  // The background is white; the red wall and the blue/green lines must show.
  int reddish = 0, nonWhite = 0;
  const cv::Mat m = img.asCvMat<cv::Mat>(mrpt::img::SHALLOW_COPY);
  for (int r = 0; r < m.rows; ++r)
    for (int c = 0; c < m.cols; ++c)
    {
      const auto px = m.at<cv::Vec3b>(r, c);  // BGR
      if (px[0] < 200 || px[1] < 200 || px[2] < 200)
        ++nonWhite;
      if (px[2] > 150 && px[1] < 100 && px[0] < 100)
        ++reddish;
    }
  EXPECT_GT(nonWhite, 200);
  EXPECT_GT(reddish, 50);
  std::filesystem::remove_all(dir);
}
