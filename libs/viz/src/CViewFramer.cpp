#include <mrpt/math/geometry.h>
#include <roislam/viz/CViewFramer.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace roislam::viz
{
namespace
{
using mrpt::math::TPoint3D;
using mrpt::math::TVector3D;

/** Camera at `eye` with optical axes right / down / forward (world). */
mrpt::poses::CPose3D cameraPose(
    const TPoint3D& eye, const TVector3D& right, const TVector3D& down, const TVector3D& forward)
{
  Eigen::Matrix3d R;  // columns: the camera's axes
  R << right.x, down.x, forward.x, right.y, down.y, forward.y, right.z, down.z, forward.z;
  return mrpt::poses::CPose3D(R, eye);
}

/** Focal length and principal point that make the points' projections
 *  span the panel less the margin (equal fx, fy), and the clip range. */
TSnapshotView fit(
    const mrpt::poses::CPose3D& pose, const std::vector<TPoint3D>& points, const TPoint3D& centre,
    unsigned width, unsigned height, double margin)
{
  double xmin = 1e30, xmax = -1e30, ymin = 1e30, ymax = -1e30, zmin = 1e30, zmax = -1e30;
  for (const auto& p : points)
  {
    const auto q = pose.inverseComposePoint(p);
    if (q.z <= 1e-6)
      continue;  // cannot happen for points inside the box (the eye is outside it)
    xmin = std::min(xmin, q.x / q.z);
    xmax = std::max(xmax, q.x / q.z);
    ymin = std::min(ymin, q.y / q.z);
    ymax = std::max(ymax, q.y / q.z);
    zmin = std::min(zmin, q.z);
    zmax = std::max(zmax, q.z);
  }
  if (xmin > xmax)
    throw std::logic_error("CViewFramer: no point in front of the camera");
  const double usableW = width * (1 - 2 * margin), usableH = height * (1 - 2 * margin);
  // A single point (or a line seen end-on) spans nothing: any focal length fits.
  const double spanX = std::max(xmax - xmin, 1e-6), spanY = std::max(ymax - ymin, 1e-6);
  const double f = std::min(usableW / spanX, usableH / spanY);
  TSnapshotView v;
  v.pose = pose;
  v.camera.ncols = width;
  v.camera.nrows = height;
  v.camera.setIntrinsicParamsFromValues(
      f, f, width / 2.0 - f * (xmin + xmax) / 2, height / 2.0 - f * (ymin + ymax) / 2);
  v.nearM = std::max(1e-3, 0.5 * zmin);
  v.farM = 2 * zmax + 1;
  v.pixelsPerMetre = f / std::max(1e-6, pose.inverseComposePoint(centre).z);
  return v;
}

TPoint3D boxCentre(const mrpt::math::TBoundingBox& box)
{
  return (box.min + box.max) * 0.5;
}

double halfDiagonal(const mrpt::math::TBoundingBox& box)
{
  return std::max(0.05, 0.5 * (box.max - box.min).norm());
}
}  // namespace

TVector3D CViewFramer::heading(const TVector3D& lookDirection) const
{
  const TVector3D h(lookDirection.x, lookDirection.y, 0);
  // A look direction that is mostly vertical (or unknown) says nothing about heading.
  if (h.norm() < 0.2 * std::max(1e-12, lookDirection.norm()) || h.norm() < 1e-12)
  {
    const double a = m_options.defaultHeadingDeg * M_PI / 180.0;
    return {std::cos(a), std::sin(a), 0};
  }
  return h.unitarize();
}

TSnapshotView CViewFramer::perspective(
    const std::vector<TPoint3D>& points, const mrpt::math::TBoundingBox& box,
    const TVector3D& heading, unsigned width, unsigned height) const
{
  const double el = m_options.elevationDeg * M_PI / 180.0;
  const TVector3D up(0, 0, 1);
  const TVector3D forward = heading * std::cos(el) - up * std::sin(el);
  const TVector3D right = mrpt::math::crossProduct3D(forward, up).unitarize();
  const TVector3D down = mrpt::math::crossProduct3D(forward, right);
  const TPoint3D centre = boxCentre(box);
  const double d = m_options.distanceFactor * halfDiagonal(box);
  const TPoint3D eye = centre - forward * d;
  return fit(
      cameraPose(eye, right, down, forward), points, centre, width, height, m_options.margin);
}

TSnapshotView CViewFramer::topDown(
    const std::vector<TPoint3D>& points, const mrpt::math::TBoundingBox& box,
    const TVector3D& heading, unsigned width, unsigned height) const
{
  // Far above with a long focal length: heights barely change the scale.
  const TVector3D forward(0, 0, -1);
  const TVector3D down = heading * -1.0;  // image up = heading
  const TVector3D right = mrpt::math::crossProduct3D(down, forward);
  const TPoint3D centre = boxCentre(box);
  const TPoint3D eye = centre + TVector3D(0, 0, 1) * (20 * halfDiagonal(box));
  return fit(
      cameraPose(eye, right, down, forward), points, centre, width, height, m_options.margin);
}
}  // namespace roislam::viz
