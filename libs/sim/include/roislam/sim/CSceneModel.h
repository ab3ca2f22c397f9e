/* The synthetic indoor scene rendered by CRgbdSimulator: a room (floor, four
 * walls, ceiling), a desk and a few boxes on it, all made of textured
 * rectangles. The same rectangles are rendered by OpenGL (makeOpenGLScene) and
 * ray-cast analytically (raycast), so tests can compare rendered depth against
 * exact geometry.
 *
 * World frame: Z up, floor at z = 0, the desk stands against the wall at
 * x = roomMax().x; the camera path of CCameraPath looks roughly along +X.
 * Scene types: "textured" (procedural text pages, posters, checkerboards,
 * noise; see ProceduralTextures.h) and "featureless" (every face a uniform
 * white, shaded per face only, the dissertation's failure case). Either can
 * be furnished: more surfaces at many orientations, as in ICL-NUIM's living
 * room, where dense depth registration (ICP) is far better constrained than
 * in the bare room.
 */
#pragma once

#include <mrpt/img/TCamera.h>
#include <mrpt/math/TPoint3D.h>
#include <mrpt/opengl/COpenGLScene.h>
#include <mrpt/poses/CPose3D.h>

#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <string>
#include <vector>

namespace roislam::sim
{
/** One planar textured rectangle. Its local frame has the origin at the
 *  centre, +X to the right and +Y up as seen from the front, +Z the outward
 *  normal (towards the viewer); texture column 0 is at x = -width/2 and row 0
 *  at y = +height/2. */
struct TTexturedRect
{
  std::string name;
  mrpt::poses::CPose3D pose;     //!< rectangle frame in the world
  double width = 1, height = 1;  //!< metres
  cv::Mat texture;               //!< CV_8UC3 BGR, already shaded
};

/** Result of a ray cast against the scene. */
struct TRayHit
{
  double distance = 0;   //!< along the (unnormalised) direction: point = origin + distance * dir
  std::size_t rect = 0;  //!< index into CSceneModel::rects()
  mrpt::math::TPoint3D point;  //!< world coordinates
};

class CSceneModel
{
 public:
  enum class TSceneType
  {
    Textured,
    Featureless
  };
  /** "textured" | "featureless"; throws std::invalid_argument otherwise. */
  static TSceneType sceneTypeFromString(const std::string& s);

  /** Builds the room. textureSeed drives every procedural texture (the
   *  geometry is fixed); texelsPerMetre is the texture density of the walls
   *  and floor (desk objects get 2.5x that). furnished adds furniture
   *  (chairs, a low table, a shelf, a cabinet, more desk objects, panels
   *  leaning on the walls), painted as the scene type says; the rest of the
   *  room, its textures included, stays as without it. */
  static CSceneModel build(
      TSceneType type, uint32_t textureSeed = 1, double texelsPerMetre = 600.0,
      bool furnished = false);

  const std::vector<TTexturedRect>& rects() const { return m_rects; }
  /** Axis-aligned bounds of the room interior (walls, floor and ceiling). */
  mrpt::math::TPoint3D roomMin() const { return m_roomMin; }
  mrpt::math::TPoint3D roomMax() const { return m_roomMax; }

  /** Nearest intersection with any rectangle for distance > 0, or nullopt. */
  std::optional<TRayHit> raycast(
      const mrpt::math::TPoint3D& origin, const mrpt::math::TVector3D& dir) const;

  /** Analytic depth (optical Z, metres) seen at pixel (u, v) by a pinhole
   *  camera (distortion ignored) whose optical frame (+Z forward, +X right,
   *  +Y down) has pose cameraPose in the world; nullopt when nothing is hit. */
  std::optional<double> depthAt(
      const mrpt::poses::CPose3D& cameraPose, const mrpt::img::TCamera& camera, double u,
      double v) const;

  /** Distance from a world point to the closest rectangle (metres). */
  double distanceToSurface(const mrpt::math::TPoint3D& p) const;

  /** OpenGL scene of unlit textured triangles, for CFBORender. */
  mrpt::opengl::COpenGLScene::Ptr makeOpenGLScene() const;

 private:
  std::vector<TTexturedRect> m_rects;
  mrpt::math::TPoint3D m_roomMin, m_roomMax;
};
}  // namespace roislam::sim
