#include <mrpt/opengl/CFBORender.h>
#include <roislam/viz/CSnapshotRenderer.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace roislam::viz
{
mrpt::img::CImage CSnapshotRenderer::render(mrpt::opengl::COpenGLScene& scene) const
{
  auto viewport = scene.getViewport("main");
  const float g = m_options.background;
  viewport->setCustomBackgroundColor(mrpt::img::TColorf(g, g, g));

  // Frame the bounding box: the orbit distance makes its diagonal fit the
  // (default 30 deg) vertical field of view with some margin.
  mrpt::math::TBoundingBox bb;
  bool hasBox = true;
  try
  {
    bb = scene.getBoundingBox();
  }
  catch (const std::exception&)
  {
    hasBox = false;
  }
  mrpt::math::TPoint3D centre(0, 0, 0);
  double diag = 2.0;
  if (hasBox && bb.min.x <= bb.max.x)
  {
    centre = (bb.min + bb.max) * 0.5;
    diag = std::max(0.5, (bb.max - bb.min).norm());
  }
  viewport->setViewportClipDistances(0.01f, static_cast<float>(20 * diag + 10));

  mrpt::opengl::CCamera camera;
  camera.setPointingAt(centre);
  camera.setZoomDistance(static_cast<float>(1.6 * diag));
  camera.setAzimuthDegrees(m_options.azimuthDeg);
  camera.setElevationDegrees(m_options.elevationDeg);

  mrpt::img::CImage image;
  try
  {
    mrpt::opengl::CFBORender fbo(m_options.width, m_options.height);
    fbo.setCamera(scene, camera);
    fbo.render_RGB(scene, image);
  }
  catch (const std::exception& e)
  {
    // MRPT exceptions span several lines; keep the first one.
    std::string what = e.what();
    what = what.substr(0, what.find('\n'));
    throw std::runtime_error("offscreen rendering failed: " + what);
  }
  return image;
}

void CSnapshotRenderer::renderToFile(
    mrpt::opengl::COpenGLScene& scene, const std::string& pngFile) const
{
  const auto image = render(scene);
  // The encoder picks the format from the extension, so keep ".png" last.
  const std::string tmp = pngFile + ".tmp.png";
  bool ok = false;
  try
  {
    ok = image.saveToFile(tmp);
  }
  catch (const std::exception&)
  {
    ok = false;
  }
  if (!ok || std::rename(tmp.c_str(), pngFile.c_str()) != 0)
  {
    std::remove(tmp.c_str());
    throw std::runtime_error(pngFile + ": cannot write the snapshot");
  }
}
}  // namespace roislam::viz
