#include "roislam/sim/CSceneModel.h"

#include <mrpt/core/bits_math.h>
#include <mrpt/img/CImage.h>
#include <mrpt/opengl/CSetOfTexturedTriangles.h>
#include <mrpt/random/RandomGenerators.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "CRoomBuilder.h"

namespace roislam::sim
{
using detail::dot;
using mrpt::math::TPoint3D;
using mrpt::math::TVector3D;

CSceneModel::TSceneType CSceneModel::sceneTypeFromString(const std::string& s)
{
  if (s == "textured")
    return TSceneType::Textured;
  if (s == "featureless")
    return TSceneType::Featureless;
  throw std::invalid_argument("unknown scene '" + s + "' (expected textured|featureless)");
}

CSceneModel CSceneModel::build(
    TSceneType type, uint32_t textureSeed, double texelsPerMetre, bool furnished)
{
  if (!(texelsPerMetre >= 50 && texelsPerMetre <= 3000))
    throw std::invalid_argument("texels per metre must be in [50, 3000]");
  CSceneModel m;
  const detail::TRoomSize r;
  m.m_roomMin = {r.x0, r.y0, 0};
  m.m_roomMax = {r.x1, r.y1, r.zTop};
  // In this order: the texture generator's draws follow it.
  detail::CRoomBuilder b(type, textureSeed, texelsPerMetre);
  detail::addRoomSurfaces(b, r);
  detail::addDesk(b, r);
  detail::addDeskObjects(b, r.deskH);
  // After everything else: the textured room's draws stay as they were.
  if (furnished)
    detail::addFurniture(b, r);
  m.m_rects = b.take();
  return m;
}

std::optional<TRayHit> CSceneModel::raycast(const TPoint3D& origin, const TVector3D& dir) const
{
  std::optional<TRayHit> best;
  for (std::size_t i = 0; i < m_rects.size(); ++i)
  {
    const auto& r = m_rects[i];
    const auto R = r.pose.getRotationMatrix();
    const TVector3D n{R(0, 2), R(1, 2), R(2, 2)};
    const TPoint3D c{r.pose.x(), r.pose.y(), r.pose.z()};
    const double denom = dot(n, dir);
    if (std::abs(denom) < 1e-12)
      continue;
    const double t = dot(n, c - origin) / denom;
    if (t <= 1e-9 || (best && t >= best->distance))
      continue;
    const TPoint3D p = origin + dir * t;
    const TVector3D rel = p - c;
    const double a = rel.x * R(0, 0) + rel.y * R(1, 0) + rel.z * R(2, 0);
    const double bb = rel.x * R(0, 1) + rel.y * R(1, 1) + rel.z * R(2, 1);
    if (std::abs(a) > r.width / 2 || std::abs(bb) > r.height / 2)
      continue;
    best = TRayHit{t, i, p};
  }
  return best;
}

std::optional<double> CSceneModel::depthAt(
    const mrpt::poses::CPose3D& cameraPose, const mrpt::img::TCamera& camera, double u,
    double v) const
{
  const auto R = cameraPose.getRotationMatrix();
  const double dc[3] = {(u - camera.cx()) / camera.fx(), (v - camera.cy()) / camera.fy(), 1.0};
  TVector3D dir{0, 0, 0};
  for (int k = 0; k < 3; ++k)
  {
    dir.x += R(0, k) * dc[k];
    dir.y += R(1, k) * dc[k];
    dir.z += R(2, k) * dc[k];
  }
  // The optical Z of dir is 1, so the ray parameter is the depth.
  const auto hit = raycast({cameraPose.x(), cameraPose.y(), cameraPose.z()}, dir);
  if (!hit)
    return std::nullopt;
  return hit->distance;
}

double CSceneModel::distanceToSurface(const TPoint3D& p) const
{
  double best = std::numeric_limits<double>::infinity();
  for (const auto& r : m_rects)
  {
    TPoint3D local;
    r.pose.inverseComposePoint(p, local);
    const double dx = std::max(0.0, std::abs(local.x) - r.width / 2);
    const double dy = std::max(0.0, std::abs(local.y) - r.height / 2);
    best = std::min(best, std::sqrt(dx * dx + dy * dy + local.z * local.z));
  }
  return best;
}

mrpt::opengl::COpenGLScene::Ptr CSceneModel::makeOpenGLScene() const
{
  auto scene = mrpt::opengl::COpenGLScene::Create();
  scene->getViewport()->setViewportClipDistances(0.05, 50.0);
  for (const auto& r : m_rects)
  {
    auto obj = mrpt::opengl::CSetOfTexturedTriangles::Create();
    // Corners in local (x right, y up) with texture (u, v) = (col, row) / size.
    const double hw = r.width / 2, hh = r.height / 2;
    const double corners[4][4] = {
        {-hw, hh, 0, 0}, {hw, hh, 1, 0}, {hw, -hh, 1, 1}, {-hw, -hh, 0, 1}};
    mrpt::math::TPoint3Df w[4];
    for (int k = 0; k < 4; ++k)
    {
      const auto g = r.pose.composePoint(TPoint3D(corners[k][0], corners[k][1], 0));
      w[k] = mrpt::math::TPoint3Df(g.x, g.y, g.z);
    }
    for (const auto& tri : {std::array<int, 3>{0, 1, 2}, std::array<int, 3>{0, 2, 3}})
    {
      mrpt::opengl::TTriangle t(w[tri[0]], w[tri[1]], w[tri[2]]);
      for (int k = 0; k < 3; ++k)
      {
        t.vertices[k].uv.x = static_cast<float>(corners[tri[k]][2]);
        t.vertices[k].uv.y = static_cast<float>(corners[tri[k]][3]);
        t.setColor(mrpt::img::TColor(255, 255, 255, 255));
      }
      obj->insertTriangle(t);
    }
    obj->assignImage(mrpt::img::CImage(r.texture, mrpt::img::DEEP_COPY));
    obj->enableLight(false);
    obj->enableTextureLinearInterpolation(true);
    scene->insert(obj);
  }
  return scene;
}
}  // namespace roislam::sim
