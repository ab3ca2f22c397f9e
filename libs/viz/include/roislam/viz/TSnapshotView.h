/* One view of a snapshot: a pinhole camera in the scene's world (optical
 * convention: +z forward, +x right, +y down, as CCamera's 6-DoF mode), its
 * intrinsics for one panel of the picture and the clip range that holds the
 * scene. Made by CViewFramer, rendered by CSnapshotRenderer, which also
 * draws the trajectories through project().
 */
#pragma once

#include <mrpt/img/TCamera.h>
#include <mrpt/math/TPoint2D.h>
#include <mrpt/math/TPoint3D.h>
#include <mrpt/poses/CPose3D.h>

#include <optional>

namespace roislam::viz
{
struct TSnapshotView
{
  mrpt::poses::CPose3D pose;  //!< optical frame in the world
  mrpt::img::TCamera camera;  //!< panel size and pinhole intrinsics (px)
  double nearM = 0.01;        //!< clip distances (m)
  double farM = 100;
  double pixelsPerMetre = 100;  //!< at the framed box's centre

  /** Pixel (u right, v down) of a world point; nullopt behind the camera. */
  std::optional<mrpt::math::TPoint2D> project(const mrpt::math::TPoint3D& world) const
  {
    const auto q = pose.inverseComposePoint(world);
    if (q.z <= 1e-9)
      return std::nullopt;
    return mrpt::math::TPoint2D(
        camera.cx() + camera.fx() * q.x / q.z, camera.cy() + camera.fy() * q.y / q.z);
  }
};
}  // namespace roislam::viz
