/* The 3-D half of the live view: the growing map (each keyframe's
 * decimated cloud, an OpenGL object placed at its keyframe's pose, so an
 * optimisation moves clouds without touching their points), the estimated
 * trajectory in blue with its keyframes marked, the ground truth in green,
 * loop-closure edges in red (a new one flashing thick yellow for a while),
 * the current camera as a frustum and a grid under the map.
 *
 * Drawn gravity-up, levelled from the first camera (CGravityFrame's
 * first-camera frame: the live view cannot wait for the ATE alignment or a
 * whole accelerometer log). The ground truth is placed so that its pose at
 * the first tracked frame coincides with the estimate's there: it shows the
 * drift as it grows, and the closures pulling it back.
 *
 * Fed and updated on the live view's drawing thread (CLiveView), never on
 * the SLAM thread; no window needed (tests build it alone).
 */
#pragma once

#include <mrpt/math/TBoundingBox.h>
#include <mrpt/opengl/CFrustum.h>
#include <mrpt/opengl/CGridPlaneXY.h>
#include <mrpt/opengl/COpenGLViewport.h>
#include <mrpt/opengl/CPointCloud.h>
#include <mrpt/opengl/CPointCloudColoured.h>
#include <mrpt/opengl/CSetOfLines.h>
#include <mrpt/poses/CPose3D.h>
#include <roislam/gui/TLiveFrame.h>
#include <roislam/io/TumTrajectory.h>

#include <cstddef>
#include <map>
#include <optional>
#include <utility>
#include <vector>

namespace roislam::gui
{
class CLiveScene
{
 public:
  /** Set in code by CLiveView (from its [LiveView] options). */
  struct TOptions
  {
    float pointSize = 2.0f;  //!< map points, pixels
    double flashS = 2.0;     //!< a new loop closure flashes this long (s)
    /** Points per keyframe kept to frame the view (bounds()). */
    std::size_t framingPointsPerKeyframe = 100;
  };

  CLiveScene();
  explicit CLiveScene(const TOptions& options);

  /** Ground truth (TUM camera poses); shown up to the current frame's time. */
  void setGroundTruth(io::TTrajectory groundTruth);
  /** A frame: trajectory, a new keyframe with its cloud, closures. `now`
   *  (s, any clock) times the flash of new closures. */
  void addFrame(const TLiveFrame& frame, double now);
  /** After an optimisation: every keyframe's pose, and the closures left. */
  void setKeyframePoses(
      const std::map<std::size_t, mrpt::poses::CPose3D>& poses,
      const std::vector<std::pair<std::size_t, std::size_t>>& loops, double now);

  /** Inserts the objects into `viewport` (once each) and brings them up
   *  to date; call with the scene locked. */
  void update(mrpt::opengl::COpenGLViewport& viewport, double now);

  /** Estimate's world -> display (identity until the first tracked frame). */
  const mrpt::poses::CPose3D& toDisplay() const { return m_toDisplay; }
  /** Display-frame extent of the map (robust) and the paths; nullopt when
   *  there is nothing yet. */
  std::optional<mrpt::math::TBoundingBox> bounds() const;
  /** Mean viewing direction of the keyframes, display frame (zero: none). */
  mrpt::math::TVector3D lookDirection() const;

  /** The estimated path in the display frame, in time order. */
  std::vector<mrpt::math::TPoint3D> trajectory() const;
  /** The ground truth drawn so far, display frame. */
  std::vector<mrpt::math::TPoint3D> groundTruthShown() const;
  /** Closures flashing at `now`. */
  std::size_t flashingClosures(double now) const;
  std::size_t keyframeClouds() const { return m_clouds.size(); }
  /** Display pose of a keyframe's cloud object (nullopt: no cloud). */
  std::optional<mrpt::poses::CPose3D> cloudPose(std::size_t keyframe) const;
  /** Display pose of the current camera's frustum (its +x is the camera's
   *  view), after update(); nullopt before the first tracked frame. */
  std::optional<mrpt::poses::CPose3D> cameraMarkerPose() const;

 private:
  struct TFramePose
  {
    double timestamp = 0;
    std::size_t reference = 0;
    mrpt::poses::CPose3D relative;
    bool isKeyframe = false;
    std::size_t keyframe = 0;
  };
  struct TLoop
  {
    std::size_t from = 0, to = 0;
    double acceptedAt = 0;
  };

  void startDisplayFrame(const TLiveFrame& frame);
  void setLoops(const std::vector<std::pair<std::size_t, std::size_t>>& loops, double now);
  /** World pose of a tracked frame in the current estimate. */
  std::optional<mrpt::poses::CPose3D> framePose(const TFramePose& f) const;
  std::optional<mrpt::math::TPoint3D> keyframePosition(std::size_t id) const;
  void rebuildPaths();
  void rebuildLoops(double now);
  void rebuildGrid();

  TOptions m_options;
  bool m_started = false;
  mrpt::poses::CPose3D m_toDisplay;
  io::TTrajectory m_groundTruth;
  /** Ground truth -> estimate's world (from the first tracked frame). */
  std::optional<mrpt::poses::CPose3D> m_gtToWorld;
  double m_lastStamp = 0;

  std::map<std::size_t, mrpt::poses::CPose3D> m_keyframePoses;
  std::vector<TFramePose> m_frames;
  std::vector<TLoop> m_loops;
  /** Keyframe clouds, and a few of their points (local frame) for bounds(). */
  std::map<std::size_t, mrpt::opengl::CPointCloudColoured::Ptr> m_clouds;
  std::map<std::size_t, std::vector<mrpt::math::TPoint3Df>> m_framing;
  /** Clouds not yet inserted into the viewport. */
  std::vector<mrpt::opengl::CPointCloudColoured::Ptr> m_newClouds;
  bool m_posesDirty = false;
  bool m_attached = false;

  mrpt::opengl::CSetOfLines::Ptr m_trajectory, m_gtLines, m_loopLines, m_flashLines;
  mrpt::opengl::CPointCloud::Ptr m_keyframeMarks;
  mrpt::opengl::CFrustum::Ptr m_camera;
  mrpt::opengl::CGridPlaneXY::Ptr m_grid;
};
}  // namespace roislam::gui
