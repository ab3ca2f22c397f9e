// The bare room: its walls, floor and ceiling, the desk and the objects on
// it (CSceneModel::build draws them in this order from the texture seed).
#include <mrpt/core/bits_math.h>

#include "CRoomBuilder.h"
#include "roislam/sim/ProceduralTextures.h"

namespace roislam::sim::detail
{
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
}  // namespace roislam::sim::detail
