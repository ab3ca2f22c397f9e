/* Chooses the snapshot's cameras so that the result fills the picture: a
 * 3-D view from behind and above the cameras (looking where they looked on
 * average, so the walls behind them, never mapped, do not hide anything) and
 * a top-down view whose "up" is the same horizontal heading, so both panels
 * read the same way. The focal length and principal point are solved so
 * that the given points (a sample of the map within its robust box, and the
 * trajectories) span the panel less a margin. Expects a gravity-up world
 * (z up). Used by CSnapshotRenderer.
 *
 * Options (code only): elevationDeg (3-D view looks down by it, default 40),
 * distanceFactor (3-D view distance over the box's half diagonal, 2.2: a
 * moderate perspective), defaultHeadingDeg (when the look direction is
 * unknown or vertical: 60, from the world's x axis), margin (fraction of the
 * panel kept free on each side, 0.04).
 */
#pragma once

#include <mrpt/math/TBoundingBox.h>
#include <roislam/viz/TSnapshotView.h>

#include <vector>

namespace roislam::viz
{
class CViewFramer
{
 public:
  struct TOptions
  {
    double elevationDeg = 40;
    double distanceFactor = 2.2;
    double defaultHeadingDeg = 60;
    double margin = 0.04;
  };

  CViewFramer() = default;
  explicit CViewFramer(const TOptions& options) : m_options(options) {}

  /** Unit horizontal heading of the views for a look direction (any length). */
  mrpt::math::TVector3D heading(const mrpt::math::TVector3D& lookDirection) const;

  /** The 3-D view of `points` inside `box`, for a width x height panel. */
  TSnapshotView perspective(
      const std::vector<mrpt::math::TPoint3D>& points, const mrpt::math::TBoundingBox& box,
      const mrpt::math::TVector3D& heading, unsigned width, unsigned height) const;

  /** The top-down view (near-orthographic: seen from far above with a long
   *  focal length). */
  TSnapshotView topDown(
      const std::vector<mrpt::math::TPoint3D>& points, const mrpt::math::TBoundingBox& box,
      const mrpt::math::TVector3D& heading, unsigned width, unsigned height) const;

  const TOptions& options() const { return m_options; }

 private:
  TOptions m_options;
};
}  // namespace roislam::viz
