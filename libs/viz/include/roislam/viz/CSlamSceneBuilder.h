/* Builds the 3-D scene of a SLAM result (map cloud or voxels, estimated
 * trajectory in blue with its keyframes, ground truth in green, a grid under
 * the map) and saves it in MRPT's .3Dscene format (opens in SceneViewer3D).
 * The content is expected gravity-up (z up, CSlamOutputWriter), so the grid
 * lies at the floor. Used by CSlamOutputWriter and CSnapshotRenderer.
 */
#pragma once

#include <mrpt/opengl/COpenGLScene.h>
#include <roislam/viz/TSceneContent.h>

#include <limits>
#include <string>

namespace roislam::viz
{
class CSlamSceneBuilder
{
 public:
  /** Not read from an ini file (the SLAM app sets them in code). */
  struct TOptions
  {
    float pointSize = 2.0f;        //!< pixels
    float trajectoryWidth = 3.0f;  //!< pixels
    float keyframeSize = 8.0f;     //!< pixels
    bool showGrid = true;          //!< a grid at the bottom of the map's (robust) bounding box
    double gridSpacing = 0;        //!< m; 0 = niceGridSpacing() of the box
    /** false: the map alone (CSnapshotRenderer draws the lines itself). */
    bool showTrajectories = true;
    /** Map points above this height (z, m) are left out (a cut-away top view). */
    double maxPointHeight = std::numeric_limits<double>::infinity();
  };

  CSlamSceneBuilder() = default;
  explicit CSlamSceneBuilder(const TOptions& options) : m_options(options) {}

  /** A new scene with the content's objects (named "map_cloud", "map_object",
   *  "trajectory", "keyframes", "ground_truth", "grid"; absent content adds
   *  nothing). */
  mrpt::opengl::COpenGLScene::Ptr build(const TSceneContent& content) const;

  /** The grid spacing build() uses for this content (m). */
  double gridSpacing(const TSceneContent& content) const;

  /** Serialises the scene to `file` through a temporary file renamed on
   *  success; throws std::runtime_error naming the file on failure. */
  static void save(const mrpt::opengl::COpenGLScene& scene, const std::string& file);

  const TOptions& options() const { return m_options; }

 private:
  TOptions m_options;
};
}  // namespace roislam::viz
