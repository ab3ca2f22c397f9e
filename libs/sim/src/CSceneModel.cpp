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

#include "roislam/sim/ProceduralTextures.h"

namespace roislam::sim
{
namespace
{
using mrpt::math::TPoint3D;
using mrpt::math::TVector3D;

double dot(const TVector3D& a, const TVector3D& b)
{
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
TVector3D cross(const TVector3D& a, const TVector3D& b)
{
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
TVector3D normalized(const TVector3D& v)
{
  return v * (1.0 / std::sqrt(dot(v, v)));
}

/** Pose of a rectangle centred at c, facing along normal n, with "up" u. */
mrpt::poses::CPose3D rectPose(const TPoint3D& c, const TVector3D& n, const TVector3D& u)
{
  const TVector3D right = cross(u, n);
  mrpt::math::CMatrixDouble33 R;
  const TVector3D cols[3] = {right, u, n};
  for (int k = 0; k < 3; ++k)
  {
    R(0, k) = cols[k].x;
    R(1, k) = cols[k].y;
    R(2, k) = cols[k].z;
  }
  mrpt::math::CVectorFixedDouble<3> t;
  t[0] = c.x;
  t[1] = c.y;
  t[2] = c.z;
  return mrpt::poses::CPose3D::FromRotationAndTranslation(R, t);
}

/** Per-face brightness of a fixed overhead light, baked into the texture so
 *  faces of different orientation differ as under real room lighting. */
double shading(const TVector3D& n)
{
  const TVector3D light = normalized({-0.35, 0.45, 0.82});
  // Mild contrast: face boundaries of the featureless room stay below the
  // Canny 250/300 thresholds of the ROI detector, as on a real white wall.
  return 0.78 + 0.22 * std::max(0.0, dot(n, light));
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

  void add(
      const std::string& name, const TPoint3D& c, const TVector3D& n, const TVector3D& up, double w,
      double h, cv::Mat texture)
  {
    TTexturedRect r;
    r.name = name;
    r.pose = rectPose(c, n, up);
    r.width = w;
    r.height = h;
    if (!m_textured)
      texture = cv::Mat(4, 4, CV_8UC3, cv::Scalar(246, 246, 246));
    texture.convertTo(r.texture, CV_8UC3, shading(n));
    m_rects.push_back(std::move(r));
  }

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
void place(cv::Mat& tex, double pxPerM, double left, double top, const cv::Mat& patch)
{
  pasteTexture(
      tex, patch,
      cv::Point(
          static_cast<int>(std::lround(left * pxPerM)),
          static_cast<int>(std::lround(top * pxPerM))));
}

cv::Size metres(double w, double h, double pxPerM)
{
  return {
      std::max(4, static_cast<int>(std::lround(w * pxPerM))),
      std::max(4, static_cast<int>(std::lround(h * pxPerM)))};
}
}  // namespace

CSceneModel::TSceneType CSceneModel::sceneTypeFromString(const std::string& s)
{
  if (s == "textured")
    return TSceneType::Textured;
  if (s == "featureless")
    return TSceneType::Featureless;
  throw std::invalid_argument("unknown scene '" + s + "' (expected textured|featureless)");
}

namespace
{
/** The room's interior and the desk, metres. */
struct TRoomSize
{
  double x0 = -1.2, x1 = 2.4, y0 = -1.6, y1 = 1.6, zTop = 2.6;
  double deskX0 = 1.6, deskY = 1.0, deskH = 0.74;
  /** Faces reach into their neighbours: no cracks at corners. */
  double overlap = 0.01;
};

/** Floor, ceiling and the four walls with their posters and pages. */
void addRoomSurfaces(CRoomBuilder& b, const TRoomSize& r)
{
  const double x0 = r.x0, x1 = r.x1, y0 = r.y0, y1 = r.y1, zTop = r.zTop, overlap = r.overlap;
  auto& rng = b.rng();
  const bool tx = b.textured();
  const double d1 = b.pxPerMetre(1.0);
  auto wallpaper = [&](cv::Size s, cv::Scalar base)
  { return tx ? makeNoiseTexture(rng, s, base, 22, 3) : cv::Mat(); };

  // Floor: wooden planks along +x.
  {
    const double w = y1 - y0 + 2 * overlap, h = x1 - x0 + 2 * overlap;
    cv::Mat t =
        tx ? makeWoodTexture(rng, b.texSize(w, h, 1), static_cast<int>(0.16 * d1)) : cv::Mat();
    b.add("floor", {(x0 + x1) / 2, 0, 0}, {0, 0, 1}, {1, 0, 0}, w, h, t);
  }
  // Ceiling: rarely seen, plain plaster at a third of the density.
  {
    const double w = y1 - y0 + 2 * overlap, h = x1 - x0 + 2 * overlap;
    cv::Mat t =
        tx ? makeNoiseTexture(rng, b.texSize(w, h, 0.33), {225, 228, 230}, 12, 2) : cv::Mat();
    b.add("ceiling", {(x0 + x1) / 2, 0, zTop}, {0, 0, -1}, {1, 0, 0}, w, h, t);
  }
  // Front wall (x = x1), seen facing +x: texture left is +y.
  {
    const double w = y1 - y0 + 2 * overlap, h = zTop + 2 * overlap;
    cv::Mat t = wallpaper(b.texSize(w, h, 1), {190, 212, 222});
    if (tx)
    {
      // Heights are measured from the wall top (z = zTop + overlap).
      place(t, d1, 0.30, 0.60, makePoster(rng, metres(0.60, 0.80, d1)));
      place(t, d1, 1.05, 0.75, makeTextPage(rng, metres(1.00, 0.70, d1), 0.035 * d1));
      place(
          t, d1, 2.25, 0.80,
          makeCheckerboard(rng, metres(0.50, 0.50, d1), static_cast<int>(0.0625 * d1)));
      place(t, d1, 2.30, 1.40, makeTextPage(rng, metres(0.30, 0.30, d1), 0.02 * d1));
      place(t, d1, 0.55, 1.48, makeTextPage(rng, metres(0.21, 0.30, d1), 0.015 * d1));
    }
    b.add("wall_front", {x1, 0, zTop / 2}, {-1, 0, 0}, {0, 0, 1}, w, h, t);
  }
  // Left wall (y = y1), seen facing +y: texture left is -x (back of the room).
  {
    const double w = x1 - x0 + 2 * overlap, h = zTop + 2 * overlap;
    cv::Mat t = wallpaper(b.texSize(w, h, 1), {200, 205, 215});
    if (tx)
    {
      place(t, d1, 2.30, 0.70, makePoster(rng, metres(0.70, 0.90, d1)));
      place(t, d1, 1.20, 0.80, makeTextPage(rng, metres(0.60, 0.80, d1), 0.03 * d1));
      place(t, d1, 3.10, 1.00, makeTextPage(rng, metres(0.30, 0.40, d1), 0.02 * d1));
      place(t, d1, 0.30, 0.90, makePoster(rng, metres(0.60, 0.50, d1)));
    }
    b.add("wall_left", {(x0 + x1) / 2, y1, zTop / 2}, {0, -1, 0}, {0, 0, 1}, w, h, t);
  }
  // Right wall (y = y0), seen facing -y: texture left is +x (the desk side).
  {
    const double w = x1 - x0 + 2 * overlap, h = zTop + 2 * overlap;
    cv::Mat t = wallpaper(b.texSize(w, h, 1), {215, 208, 195});
    if (tx)
    {
      place(t, d1, 0.35, 0.70, makeTextPage(rng, metres(0.55, 0.75, d1), 0.028 * d1));
      place(t, d1, 1.20, 0.60, makePoster(rng, metres(0.80, 0.60, d1)));
      place(
          t, d1, 1.30, 1.35,
          makeCheckerboard(rng, metres(0.60, 0.30, d1), static_cast<int>(0.05 * d1)));
      place(t, d1, 2.50, 0.80, makePoster(rng, metres(0.50, 0.70, d1)));
    }
    b.add("wall_right", {(x0 + x1) / 2, y0, zTop / 2}, {0, 1, 0}, {0, 0, 1}, w, h, t);
  }
  // Back wall (x = x0): behind the camera, half density.
  {
    const double w = y1 - y0 + 2 * overlap, h = zTop + 2 * overlap;
    cv::Mat t =
        tx ? makeNoiseTexture(rng, b.texSize(w, h, 0.5), {205, 215, 205}, 22, 2) : cv::Mat();
    if (tx)
      place(t, 0.5 * d1, 1.2, 0.8, makePoster(rng, metres(0.8, 0.6, 0.5 * d1)));
    b.add("wall_back", {x0, 0, zTop / 2}, {1, 0, 0}, {0, 0, 1}, w, h, t);
  }
}

/** The desk: a solid wooden block against the front wall, papers on top. */
void addDesk(CRoomBuilder& b, const TRoomSize& r)
{
  const double x1 = r.x1, deskX0 = r.deskX0, deskY = r.deskY, deskH = r.deskH;
  auto& rng = b.rng();
  const bool tx = b.textured();
  const double dDesk = 1.5;
  const double dk = b.pxPerMetre(dDesk);
  b.addBox(
      "desk", (deskX0 + x1) / 2, 0, 0, x1 - deskX0, 2 * deskY, deskH, 0.0,
      [&](int face, double w, double h)
      {
        if (!tx)
          return cv::Mat();
        cv::Mat t = makeWoodTexture(rng, b.texSize(w, h, dDesk), static_cast<int>(0.12 * dk));
        if (face == 4)
        {  // top: rows run along +x; papers and a mouse pad
          place(t, dk, 0.15, 0.45, makeTextPage(rng, metres(0.21, 0.297, dk), 0.012 * dk));
          place(t, dk, 1.45, 0.40, makeTextPage(rng, metres(0.297, 0.21, dk), 0.012 * dk));
          place(t, dk, 0.95, 0.50, makePoster(rng, metres(0.25, 0.22, dk)));
        }
        return t;
      });
}

/** The objects on the desk, with the densest textures (seen from about 1 m). */
void addDeskObjects(CRoomBuilder& b, double deskH)
{
  auto& rng = b.rng();
  const bool tx = b.textured();
  const double dObj = 2.5;
  const double dob = b.pxPerMetre(dObj);
  b.addBox(
      "box_cereal", 1.85, -0.45, deskH, 0.08, 0.28, 0.36, mrpt::DEG2RAD(10.0),
      [&](int face, double w, double h)
      {
        if (!tx)
          return cv::Mat();
        const cv::Size s = b.texSize(w, h, dObj);
        if (face == 0)
        {
          cv::Mat t = makePoster(rng, s);
          place(t, dob, 0.02, 0.12, makeTextPage(rng, metres(w - 0.04, 0.16, dob), 0.011 * dob));
          return t;
        }
        return face == 4 ? makeNoiseTexture(rng, s, {60, 90, 200}, 40, 2)
                         : makeTextPage(rng, s, 0.009 * dob);
      });
  b.addBox(
      "box_book", 1.95, 0.40, deskH, 0.30, 0.22, 0.10, mrpt::DEG2RAD(-15.0),
      [&](int face, double w, double h)
      {
        if (!tx)
          return cv::Mat();
        const cv::Size s = b.texSize(w, h, dObj);
        if (face == 4)
          return makeTextPage(rng, s, 0.010 * dob);
        return makeNoiseTexture(rng, s, {40, 40, 140}, 35, 2);
      });
  b.addBox(
      "box_cube", 1.80, 0.02, deskH, 0.20, 0.20, 0.20, mrpt::DEG2RAD(30.0),
      [&](int face, double w, double h)
      {
        if (!tx)
          return cv::Mat();
        const cv::Size s = b.texSize(w, h, dObj);
        switch (face)
        {
          case 0:
            return makeTextPage(rng, s, 0.012 * dob);
          case 1:
          case 2:
            return makeCheckerboard(rng, s, static_cast<int>((0.02 + 0.01 * face) * dob));
          case 3:
            return makePoster(rng, s);
          default:
            return makeNoiseTexture(rng, s, {120, 160, 120}, 45, 2);
        }
      });
  b.addBox(
      "box_monitor", 2.25, 0.05, deskH, 0.05, 0.55, 0.38, 0.0,
      [&](int face, double w, double h)
      {
        if (!tx)
          return cv::Mat();
        const cv::Size s = b.texSize(w, h, dObj);
        if (face == 0)
        {  // the screen: dark frame around a page of text
          cv::Mat t(s, CV_8UC3, cv::Scalar(30, 30, 30));
          place(
              t, dob, 0.02, 0.02, makeTextPage(rng, metres(w - 0.04, h - 0.04, dob), 0.011 * dob));
          return t;
        }
        return makeNoiseTexture(rng, s, {50, 50, 50}, 20, 2);
      });
}

/** The distance furniture textures are drawn for (their detail per metre). */
constexpr double kFurnitureViewDistanceM = 2.0;

/** The furniture's boxes (chairs, a bin, a shelf, a cabinet, a low table,
 *  objects on the desk), each face textured from the scene's seed. */
void addFurnitureBoxes(CRoomBuilder& b, const TRoomSize& r)
{
  auto& rng = b.rng();
  const double dObj = kFurnitureViewDistanceM;
  const double dob = b.pxPerMetre(dObj);
  // Every face gets a texture of its own kind, drawn from the scene's seed.
  auto anyFace = [&](cv::Scalar base)
  {
    return [&, base](int face, double w, double h)
    {
      if (!b.textured())
        return cv::Mat();
      const cv::Size s = b.texSize(w, h, dObj);
      // A page or a poster on a face a few centimetres wide can be all margin.
      if (std::min(w, h) < 0.12)
        return makeNoiseTexture(rng, s, base, 40, 2);
      switch ((face + static_cast<int>(rng.drawUniform32bit() % 4)) % 4)
      {
        case 0:
          return makeTextPage(rng, s, 0.012 * dob);
        case 1:
          return makePoster(rng, s);
        case 2:
          return makeWoodTexture(rng, s, std::max(4, static_cast<int>(0.05 * dob)));
        default:
          return makeNoiseTexture(rng, s, base, 40, 2);
      }
    };
  };
  struct TBox
  {
    const char* name;
    double x, y, z0, sx, sy, sz, yawDeg;
    cv::Scalar colour;
  };
  const double dh = r.deskH;
  const TBox boxes[] = {
      // two chairs before the desk: seat and back
      {"chair1_seat", 1.30, -0.60, 0.00, 0.45, 0.45, 0.46, 20, {40, 70, 120}},
      {"chair1_back", 1.10, -0.67, 0.46, 0.05, 0.42, 0.45, 20, {40, 70, 120}},
      {"chair2_seat", 1.25, 0.65, 0.00, 0.45, 0.45, 0.46, -35, {90, 60, 40}},
      {"chair2_back", 1.06, 0.78, 0.46, 0.05, 0.42, 0.48, -35, {90, 60, 40}},
      {"bin", 1.38, 0.08, 0.00, 0.26, 0.26, 0.34, 45, {60, 120, 60}},
      // a shelf unit along the left wall and a cabinet along the right one
      {"shelf", 1.80, 1.40, 0.00, 0.90, 0.36, 1.70, 0, {100, 140, 180}},
      {"shelf_box1", 1.55, 1.40, 1.70, 0.25, 0.20, 0.22, 12, {150, 80, 80}},
      {"shelf_box2", 2.05, 1.42, 1.70, 0.18, 0.15, 0.35, -20, {80, 150, 150}},
      {"cabinet", 1.05, -1.38, 0.00, 0.80, 0.40, 0.85, 0, {170, 170, 150}},
      {"cabinet_vase", 0.95, -1.35, 0.85, 0.16, 0.16, 0.30, 45, {30, 30, 160}},
      {"cabinet_books", 1.25, -1.40, 0.85, 0.28, 0.22, 0.24, -10, {120, 40, 120}},
      // more on the desk, at other angles
      {"desk_lamp_base", 2.10, -0.70, dh, 0.16, 0.16, 0.04, 30, {20, 20, 20}},
      {"desk_lamp_pole", 2.10, -0.70, dh + 0.04, 0.03, 0.03, 0.45, 30, {20, 20, 20}},
      {"desk_lamp_head", 2.02, -0.66, dh + 0.42, 0.22, 0.10, 0.08, 30, {200, 200, 60}},
      {"desk_stack1", 1.75, 0.70, dh, 0.24, 0.30, 0.06, 25, {60, 60, 60}},
      {"desk_stack2", 1.77, 0.71, dh + 0.06, 0.21, 0.28, 0.05, 5, {140, 100, 60}},
      {"desk_mug", 1.72, -0.30, dh, 0.09, 0.09, 0.11, 40, {220, 220, 240}},
      {"desk_tray", 2.18, 0.75, dh, 0.35, 0.26, 0.05, -40, {70, 90, 110}},
      // a low table in the middle of the room, with a box on it
      {"table", 0.95, 0.00, 0.00, 0.40, 0.60, 0.42, 8, {120, 100, 80}},
      {"table_box", 0.95, 0.10, 0.42, 0.18, 0.24, 0.12, 50, {40, 140, 200}},
  };
  for (const auto& bx : boxes)
    b.addBox(
        bx.name, bx.x, bx.y, bx.z0, bx.sx, bx.sy, bx.sz, mrpt::DEG2RAD(bx.yawDeg),
        anyFace(bx.colour));
}

/** Panels leaning on the walls and the desk (normals neither vertical nor
 *  horizontal). */
void addLeaningPanels(CRoomBuilder& b, const TRoomSize& r)
{
  auto& rng = b.rng();
  const double dObj = kFurnitureViewDistanceM;
  const double dh = r.deskH;
  struct TPanel
  {
    const char* name;
    TPoint3D c;
    TVector3D n, up;
    double w, h;
  };
  const TPanel panels[] = {
      {"board_front",
       {2.28, -1.25, 0.55},
       normalized({-1, 0.25, 0.35}),
       normalized({0.35, 0, 1}),
       0.50,
       1.00},
      {"board_left",
       {0.60, 1.45, 0.45},
       normalized({0.2, -1, 0.3}),
       normalized({0, 0.3, 1}),
       0.70,
       0.80},
      {"laptop_screen",
       {1.72, 0.30, dh + 0.12},
       normalized({-1, 0.3, 0.45}),
       normalized({0.45, 0, 1}),
       0.32,
       0.22},
  };
  for (const auto& p : panels)
  {
    // The up vector is made orthogonal to the normal.
    const TVector3D up = normalized(p.up - p.n * dot(p.up, p.n));
    b.add(
        p.name, p.c, p.n, up, p.w, p.h,
        b.textured() ? makePoster(rng, b.texSize(p.w, p.h, dObj)) : cv::Mat());
  }
}

/** The furniture (CSceneModel::build's furnished): surfaces at many
 *  orientations and distances between the camera and the walls, as in a
 *  furnished living room (ICL-NUIM's). The bare room is mostly three
 *  families of parallel planes; there OpenCV's RgbdICPOdometry reads 48 mm
 *  on the ICL-like loop, furnished 26 mm, and furnished with smooth depth
 *  5 mm (README "The reference odometry where ICP is well constrained").
 *  Only yaw-rotated boxes and tilted panels: every face stays a rectangle,
 *  so ray casting and rendering agree exactly.
 *  Drawn after the room, so the bare room's faces and textures stay as
 *  they were: boxes first, then panels (the order their textures are
 *  drawn from the seed in). */
void addFurniture(CRoomBuilder& b, const TRoomSize& r)
{
  addFurnitureBoxes(b, r);
  addLeaningPanels(b, r);
}
}  // namespace

CSceneModel CSceneModel::build(
    TSceneType type, uint32_t textureSeed, double texelsPerMetre, bool furnished)
{
  if (!(texelsPerMetre >= 50 && texelsPerMetre <= 3000))
    throw std::invalid_argument("texels per metre must be in [50, 3000]");
  CSceneModel m;
  const TRoomSize r;
  m.m_roomMin = {r.x0, r.y0, 0};
  m.m_roomMax = {r.x1, r.y1, r.zTop};
  // In this order: the texture generator's draws follow it.
  CRoomBuilder b(type, textureSeed, texelsPerMetre);
  addRoomSurfaces(b, r);
  addDesk(b, r);
  addDeskObjects(b, r.deskH);
  // After everything else: the textured room's draws stay as they were.
  if (furnished)
    addFurniture(b, r);
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
