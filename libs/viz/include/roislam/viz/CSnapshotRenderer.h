/* Off-screen (headless, EGL) picture of a SLAM result that a user reads at a
 * glance, rendered with mrpt::opengl::CFBORender. Two panels side by side:
 * left a 3-D view from behind and above the cameras, right a top-down view
 * (map points higher than the cameras cut away, so ceilings do not hide the
 * floor plan), both framed by CViewFramer so the map fills them. The map and
 * its grid are rendered by OpenGL; the trajectories are drawn over them,
 * thick: ground truth in green (wider, underneath), the estimate in blue
 * with its keyframes marked, a scale bar in the top view, and a legend in a
 * header strip above the panels (TSceneContent::legend, the colours, the
 * grid spacing), where it hides nothing. The content is expected gravity-up
 * (z up). Used by CSlamOutputWriter for snapshot.png.
 */
#pragma once

#include <mrpt/img/CImage.h>
#include <roislam/viz/CSlamSceneBuilder.h>
#include <roislam/viz/CViewFramer.h>
#include <roislam/viz/TSceneContent.h>
#include <roislam/viz/TSnapshotView.h>

#include <string>
#include <vector>

namespace roislam::viz
{
class CSnapshotRenderer
{
 public:
  /** Not read from an ini file (the SLAM app sets them in code). */
  struct TOptions
  {
    unsigned int width = 1600;  //!< pixels, both panels
    unsigned int height = 700;  //!< pixels
    bool topView = true;        //!< false: the 3-D view alone, full width
    /** Background grey level in [0,1]. */
    float background = 1.0f;
    int trajectoryPx = 4;        //!< line thickness of the estimate (ground truth: + 4)
    int keyframePx = 4;          //!< radius of the keyframe marks
    unsigned int headerPx = 34;  //!< legend strip above the panels (with overlays)
    /** Draw trajectories, keyframes and legend over the render. */
    bool overlays = true;
    /** Top view: map points higher than the highest camera by more than
     *  this are cut away (m). */
    double cutAboveCamerasM = 0.3;
    /** The views frame the map's points between these quantiles on each
     *  axis (robustBounds): sparse far readings may fall off the edges. */
    double framingQuantile = 0.03;
    CViewFramer::TOptions framing;
  };

  CSnapshotRenderer() = default;
  explicit CSnapshotRenderer(const TOptions& options) : m_options(options) {}

  /** The cameras render() uses: the 3-D view, then (with topView) the top
   *  view; pixels are those of each panel (panels start at y = headerHeight(),
   *  the top view's at x = panelWidth()). Empty when the content has nothing
   *  to show. */
  std::vector<TSnapshotView> views(const TSceneContent& content) const;
  unsigned int panelWidth() const;
  unsigned int panelHeight() const;
  unsigned int headerHeight() const;

  /** Renders the picture (background only when the content is empty).
   *  Throws std::runtime_error when no rendering context can be created. */
  mrpt::img::CImage render(const TSceneContent& content) const;

  /** render() and save as PNG through a temporary file renamed on success;
   *  throws std::runtime_error naming the file on failure. */
  void renderToFile(const TSceneContent& content, const std::string& pngFile) const;

  const TOptions& options() const { return m_options; }

 private:
  TOptions m_options;
};
}  // namespace roislam::viz
