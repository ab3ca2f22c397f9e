#include "CRoomBuilder.h"

#include "roislam/sim/ProceduralTextures.h"

namespace roislam::sim::detail
{
namespace
{
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
}  // namespace

void CRoomBuilder::add(
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
}  // namespace roislam::sim::detail
