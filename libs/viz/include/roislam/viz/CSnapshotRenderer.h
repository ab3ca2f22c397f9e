/* Off-screen (headless, EGL) rendering of a scene to a PNG with
 * mrpt::opengl::CFBORender, from an orbit camera that frames the scene's
 * bounding box. Used by the SLAM app for snapshot.png.
 */
#pragma once

#include <mrpt/img/CImage.h>
#include <mrpt/opengl/COpenGLScene.h>

#include <string>

namespace roislam::viz
{
class CSnapshotRenderer
{
 public:
  /** Not read from an ini file (the SLAM app sets them in code). */
  struct TOptions
  {
    unsigned int width = 1024;  //!< pixels
    unsigned int height = 768;  //!< pixels
    float azimuthDeg = -60;     //!< orbit camera azimuth
    float elevationDeg = 35;    //!< orbit camera elevation
    /** Background grey level in [0,1]. */
    float background = 1.0f;
  };

  CSnapshotRenderer() = default;
  explicit CSnapshotRenderer(const TOptions& options) : m_options(options) {}

  /** Renders the scene. The scene's main viewport background is set; the
   *  camera points at the centre of the scene's bounding box from a distance
   *  that frames it. Throws std::runtime_error when no rendering context can
   *  be created. */
  mrpt::img::CImage render(mrpt::opengl::COpenGLScene& scene) const;

  /** render() and save as PNG through a temporary file renamed on success;
   *  throws std::runtime_error naming the file on failure. */
  void renderToFile(mrpt::opengl::COpenGLScene& scene, const std::string& pngFile) const;

  const TOptions& options() const { return m_options; }

 private:
  TOptions m_options;
};
}  // namespace roislam::viz
