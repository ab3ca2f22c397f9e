// The furnished room's furniture, drawn after the bare room (see addFurniture).
#include <mrpt/core/bits_math.h>

#include "CRoomBuilder.h"
#include "roislam/sim/ProceduralTextures.h"

namespace roislam::sim::detail
{
namespace
{
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
}  // namespace

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
}  // namespace roislam::sim::detail
