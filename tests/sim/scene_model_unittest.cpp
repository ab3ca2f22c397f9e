// CSceneModel: analytic geometry of the synthetic room (no OpenGL needed).
#include <gtest/gtest.h>
#include <mrpt/core/bits_math.h>
#include <roislam/sim/CSceneModel.h>

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

using roislam::sim::CSceneModel;

namespace
{
mrpt::img::TCamera fr1Like()
{
  mrpt::img::TCamera c;
  c.ncols = 640;
  c.nrows = 480;
  c.fx(517.3);
  c.fy(516.5);
  c.cx(318.6);
  c.cy(255.3);
  return c;
}
// Optical frame looking along world +X from p (body x fwd, y left, z up).
mrpt::poses::CPose3D lookingAlongX(double x, double y, double z, double pitchDeg = 0)
{
  return mrpt::poses::CPose3D(x, y, z, 0, mrpt::DEG2RAD(pitchDeg), 0) +
         mrpt::poses::CPose3D(0, 0, 0, -M_PI / 2, 0, -M_PI / 2);
}
}  // namespace

TEST(SceneModel, SceneTypeParsing)
{
  EXPECT_EQ(CSceneModel::sceneTypeFromString("textured"), CSceneModel::TSceneType::Textured);
  EXPECT_EQ(CSceneModel::sceneTypeFromString("featureless"), CSceneModel::TSceneType::Featureless);
  EXPECT_THROW(CSceneModel::sceneTypeFromString("Textured"), std::invalid_argument);
}

TEST(SceneModel, FrontWallDepthIsAnalytic)
{
  const auto m = CSceneModel::build(CSceneModel::TSceneType::Featureless);
  const double wallX = m.roomMax().x;
  // Camera at 2 m height looks straight at the front wall above the desk.
  const auto pose = lookingAlongX(0.0, 0.0, 2.0);
  const auto cam = fr1Like();
  const auto zc = m.depthAt(pose, cam, cam.cx(), cam.cy());
  ASSERT_TRUE(zc.has_value());
  EXPECT_NEAR(*zc, wallX, 1e-9);
  // Depth (not range) is constant over a fronto-parallel plane.
  const auto zs = m.depthAt(pose, cam, 20.0, 200.0);
  ASSERT_TRUE(zs.has_value());
  EXPECT_NEAR(*zs, wallX, 1e-9);
}

TEST(SceneModel, FloorDepthIsAnalytic)
{
  const auto m = CSceneModel::build(CSceneModel::TSceneType::Featureless);
  // Looking 60 deg down from 1 m: the image centre ray hits the floor at range 1/sin(60).
  const auto pose = lookingAlongX(-0.5, 1.2, 1.0, 60.0);
  const auto cam = fr1Like();
  const auto z = m.depthAt(pose, cam, cam.cx(), cam.cy());
  ASSERT_TRUE(z.has_value());
  EXPECT_NEAR(*z, 1.0 / std::sin(mrpt::DEG2RAD(60.0)), 1e-9);
  // A row lower sees the floor closer.
  const auto zLow = m.depthAt(pose, cam, cam.cx(), cam.cy() + 100);
  ASSERT_TRUE(zLow.has_value());
  EXPECT_LT(*zLow, *z);
}

TEST(SceneModel, RoomIsClosedAndHitsLieOnSurfaces)
{
  const auto m = CSceneModel::build(CSceneModel::TSceneType::Featureless);
  const mrpt::math::TPoint3D o(0.3, 0.1, 1.2);
  int n = 0;
  for (double az = 0; az < 2 * M_PI; az += 0.3)
    for (double el = -1.4; el <= 1.4; el += 0.35)
    {
      const mrpt::math::TVector3D d(
          std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
      const auto hit = m.raycast(o, d);
      ASSERT_TRUE(hit.has_value()) << "ray escaped the room at az " << az << " el " << el;
      EXPECT_LT(m.distanceToSurface(hit->point), 1e-9);
      ++n;
    }
  EXPECT_GT(n, 100);
  // A point in mid-air is away from every surface.
  EXPECT_GT(m.distanceToSurface(o), 0.5);
}

TEST(SceneModel, FeaturelessTexturesAreUniformTexturedAreDetailed)
{
  const auto plain = CSceneModel::build(CSceneModel::TSceneType::Featureless);
  const auto rich = CSceneModel::build(CSceneModel::TSceneType::Textured, 1, 300.0);
  ASSERT_EQ(plain.rects().size(), rich.rects().size());
  for (std::size_t i = 0; i < plain.rects().size(); ++i)
  {
    cv::Mat mean, sd;
    cv::meanStdDev(plain.rects()[i].texture, mean, sd);
    EXPECT_EQ(cv::norm(sd), 0.0) << plain.rects()[i].name;
    cv::meanStdDev(rich.rects()[i].texture, mean, sd);
    EXPECT_GT(cv::norm(sd), 3.0) << rich.rects()[i].name;
  }
}

TEST(SceneModel, TexturesAreDeterministicPerSeed)
{
  const auto a = CSceneModel::build(CSceneModel::TSceneType::Textured, 7, 200.0);
  const auto b = CSceneModel::build(CSceneModel::TSceneType::Textured, 7, 200.0);
  const auto c = CSceneModel::build(CSceneModel::TSceneType::Textured, 8, 200.0);
  const auto& ta = a.rects()[2].texture;  // front wall
  EXPECT_EQ(cv::norm(ta, b.rects()[2].texture, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(ta, c.rects()[2].texture, cv::NORM_L1), 0.0);
}

TEST(SceneModel, RejectsAbsurdTextureDensity)
{
  EXPECT_THROW(
      CSceneModel::build(CSceneModel::TSceneType::Textured, 1, 1.0), std::invalid_argument);
}
