/* Builds the 3-D scene of a SLAM result (map cloud or voxels, estimated
 * trajectory in blue, ground truth in green) and saves it in MRPT's
 * .3Dscene format (opens in SceneViewer3D). Used by the SLAM app at the end of
 * a run and by CSnapshotRenderer's callers.
 */
#pragma once

#include <mrpt/opengl/COpenGLScene.h>
#include <roislam/viz/TSceneContent.h>

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
    bool showGrid = true;          //!< a 1 m grid under the scene's bounding box
  };

  CSlamSceneBuilder() = default;
  explicit CSlamSceneBuilder(const TOptions& options) : m_options(options) {}

  /** A new scene with the content's objects (named "map_cloud", "map_object",
   *  "trajectory", "ground_truth", "grid"; absent content adds nothing). */
  mrpt::opengl::COpenGLScene::Ptr build(const TSceneContent& content) const;

  /** Serialises the scene to `file` through a temporary file renamed on
   *  success; throws std::runtime_error naming the file on failure. */
  static void save(const mrpt::opengl::COpenGLScene& scene, const std::string& file);

  const TOptions& options() const { return m_options; }

 private:
  TOptions m_options;
};
}  // namespace roislam::viz
