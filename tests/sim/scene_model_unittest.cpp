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

TEST(SceneModel, FurnitureAddsSurfacesAndLeavesTheRoomAsItWas)
{
  const auto bare = CSceneModel::build(CSceneModel::TSceneType::Textured, 3, 200.0);
  const auto furnished = CSceneModel::build(CSceneModel::TSceneType::Textured, 3, 200.0, true);
  ASSERT_GT(furnished.rects().size(), bare.rects().size() + 50);
  // The bare room's faces come first, textures and all (drawn before the furniture's).
  for (std::size_t i = 0; i < bare.rects().size(); ++i)
  {
    const auto& a = bare.rects()[i];
    const auto& b = furnished.rects()[i];
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.pose, b.pose) << a.name;
    EXPECT_EQ(cv::norm(a.texture, b.texture, cv::NORM_INF), 0.0) << a.name;
  }
  // Every added face lies inside the room and is textured; some are tilted
  // (normals neither horizontal nor vertical): the point of furnishing.
  int tilted = 0;
  for (std::size_t i = bare.rects().size(); i < furnished.rects().size(); ++i)
  {
    const auto& r = furnished.rects()[i];
    EXPECT_GT(r.pose.x(), bare.roomMin().x) << r.name;
    EXPECT_LT(r.pose.x(), bare.roomMax().x) << r.name;
    EXPECT_GT(r.pose.y(), bare.roomMin().y) << r.name;
    EXPECT_LT(r.pose.y(), bare.roomMax().y) << r.name;
    EXPECT_GE(r.pose.z(), 0.0) << r.name;
    cv::Mat mean, sd;
    cv::meanStdDev(r.texture, mean, sd);
    EXPECT_GT(cv::norm(sd), 3.0) << r.name;
    const auto R = r.pose.getRotationMatrix();
    const double nz = std::abs(R(2, 2));
    tilted += nz > 0.1 && nz < 0.9;
  }
  EXPECT_GE(tilted, 3);
  // From the camera path's start, looking down at the room, furniture is hit.
  const auto pose = lookingAlongX(0.1, 0.0, 1.35, 30.0);
  const auto cam = fr1Like();
  int onFurniture = 0, hits = 0;
  for (int v = 10; v < 480; v += 20)
    for (int u = 10; u < 640; u += 20)
    {
      const auto R = pose.getRotationMatrix();
      const double dc[3] = {(u - cam.cx()) / cam.fx(), (v - cam.cy()) / cam.fy(), 1.0};
      mrpt::math::TVector3D dir(0, 0, 0);
      for (int k = 0; k < 3; ++k)
      {
        dir.x += R(0, k) * dc[k];
        dir.y += R(1, k) * dc[k];
        dir.z += R(2, k) * dc[k];
      }
      const auto hit = furnished.raycast({pose.x(), pose.y(), pose.z()}, dir);
      ASSERT_TRUE(hit.has_value());
      ++hits;
      onFurniture += hit->rect >= bare.rects().size();
      EXPECT_LT(furnished.distanceToSurface(hit->point), 1e-9);
    }
  EXPECT_GT(onFurniture, hits / 10);
}

TEST(SceneModel, FeaturelessFurnitureIsUniformToo)
{
  const auto m = CSceneModel::build(CSceneModel::TSceneType::Featureless, 1, 200.0, true);
  const auto bare = CSceneModel::build(CSceneModel::TSceneType::Featureless, 1, 200.0);
  ASSERT_GT(m.rects().size(), bare.rects().size());
  for (const auto& r : m.rects())
  {
    cv::Mat mean, sd;
    cv::meanStdDev(r.texture, mean, sd);
    EXPECT_EQ(cv::norm(sd), 0.0) << r.name;
  }
}
