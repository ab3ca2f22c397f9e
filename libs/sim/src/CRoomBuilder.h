#pragma once
// Private to libs/sim: the room's builder and the scene's furnishing, shared
// by CSceneModel.cpp, RoomSurfaces.cpp and RoomFurniture.cpp (split so no
// file passes 600 lines).

#include <mrpt/math/TPoint3D.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/random/RandomGenerators.h>

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "roislam/sim/CSceneModel.h"

namespace roislam::sim::detail
{
using mrpt::math::TPoint3D;
using mrpt::math::TVector3D;

inline double dot(const TVector3D& a, const TVector3D& b)
{
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline TVector3D cross(const TVector3D& a, const TVector3D& b)
{
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline TVector3D normalized(const TVector3D& v)
{
  return v * (1.0 / std::sqrt(dot(v, v)));
}

/** Builds rectangles and their textures; the "painter" callbacks receive the
 *  texture at the rectangle's density and draw on it. */
class CRoomBuilder
{
 public:
  CRoomBuilder(CSceneModel::TSceneType type, uint32_t seed, double density)
      : m_textured(type == CSceneModel::TSceneType::Textured), m_rng(seed), m_density(density)
  {
  }

  mrpt::random::CRandomGenerator& rng() { return m_rng; }
  bool textured() const { return m_textured; }

  /** Texture size in pixels for a w x h metre face at densityScale. */
  cv::Size texSize(double w, double h, double densityScale) const
  {
    return {
        std::max(4, static_cast<int>(std::lround(w * m_density * densityScale))),
        std::max(4, static_cast<int>(std::lround(h * m_density * densityScale)))};
  }
  double pxPerMetre(double densityScale) const { return m_density * densityScale; }

  /** A w x h metre rectangle centred at c, facing along n, with "up" up;
   *  shaded by its orientation (plain white in the featureless room). */
  void add(
      const std::string& name, const TPoint3D& c, const TVector3D& n, const TVector3D& up, double w,
      double h, cv::Mat texture);

  /** An axis-aligned (up to yaw) box standing on z = z0; the bottom face is
   *  omitted (never visible). faces[] painters: -x, +x, -y, +y, top. */
  template <class PAINT>
  void addBox(
      const std::string& name, double cx, double cy, double z0, double sx, double sy, double sz,
      double yaw, PAINT&& paint)
  {
    const double c = std::cos(yaw), s = std::sin(yaw);
    const TVector3D ex{c, s, 0}, ey{-s, c, 0}, ez{0, 0, 1};
    const TPoint3D centre{cx, cy, z0 + sz / 2};
    struct Face
    {
      const char* tag;
      TVector3D n, up;
      double w, h, offset;
    };
    const Face faces[] = {
        {"-x", ex * -1.0, ez, sy, sz, sx / 2},
        {"+x", ex, ez, sy, sz, sx / 2},
        {"-y", ey * -1.0, ez, sx, sz, sy / 2},
        {"+y", ey, ez, sx, sz, sy / 2},
        {"top", ez, ex, sy, sx, sz / 2}};
    for (int i = 0; i < 5; ++i)
    {
      const Face& f = faces[i];
      const TPoint3D fc = centre + f.n * f.offset;
      add(name + f.tag, fc, f.n, f.up, f.w, f.h, paint(i, f.w, f.h));
    }
  }

  std::vector<TTexturedRect> take() { return std::move(m_rects); }

 private:
  bool m_textured;
  mrpt::random::CRandomGenerator m_rng;
  double m_density;
  std::vector<TTexturedRect> m_rects;
};

/** Places a patch of (w x h) metres with its top-left corner at (left, top)
 *  metres from the texture's top-left corner. */
void place(cv::Mat& tex, double pxPerM, double left, double top, const cv::Mat& patch);

/** Texture size in pixels of a w x h metre patch at pxPerM. */
cv::Size metres(double w, double h, double pxPerM);

/** The room's interior and the desk, metres. */
struct TRoomSize
{
  double x0 = -1.2, x1 = 2.4, y0 = -1.6, y1 = 1.6, zTop = 2.6;
  double deskX0 = 1.6, deskY = 1.0, deskH = 0.74;
  /** Faces reach into their neighbours: no cracks at corners. */
  double overlap = 0.01;
};

/** Floor, ceiling and the four walls with their posters and pages. */
void addRoomSurfaces(CRoomBuilder& b, const TRoomSize& r);
/** The desk: a solid wooden block against the front wall, papers on top. */
void addDesk(CRoomBuilder& b, const TRoomSize& r);
/** The objects on the desk, with the densest textures (seen from about 1 m). */
void addDeskObjects(CRoomBuilder& b, double deskH);
/** The furniture of the furnished room (CSceneModel::build's furnished). */
void addFurniture(CRoomBuilder& b, const TRoomSize& r);
}  // namespace roislam::sim::detail
