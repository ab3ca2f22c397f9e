#include <mrpt/opengl/CFBORender.h>
#include <roislam/viz/CSnapshotRenderer.h>
#include <roislam/viz/SceneBounds.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace roislam::viz
{
namespace
{
using mrpt::math::TPoint3D;

// BGR, as CImage stores colour.
const cv::Scalar kEstimateColour(220, 60, 0);
const cv::Scalar kGroundTruthColour(0, 160, 0);
const cv::Scalar kKeyframeColour(120, 30, 0);
const cv::Scalar kTextColour(40, 40, 40);
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;

/** What the framing must keep in view: the map's points within its robust
 *  box (a sample) and every trajectory position. */
std::vector<TPoint3D> framingPoints(const TSceneContent& c, const mrpt::math::TBoundingBox& box)
{
  std::vector<TPoint3D> pts;
  const std::size_t step = std::max<std::size_t>(1, c.cloud.size() / 5000);
  for (std::size_t i = 0; i < c.cloud.size(); i += step)
  {
    float x, y, z;
    c.cloud.getPoint(i, x, y, z);
    if (x >= box.min.x && x <= box.max.x && y >= box.min.y && y <= box.max.y && z >= box.min.z &&
        z <= box.max.z)
      pts.emplace_back(x, y, z);
  }
  for (const auto* list : {&c.trajectory, &c.groundTruth, &c.keyframes})
    pts.insert(pts.end(), list->begin(), list->end());
  return pts;
}

double highestCamera(const TSceneContent& c)
{
  double top = -std::numeric_limits<double>::infinity();
  for (const auto* list : {&c.trajectory, &c.groundTruth})
    for (const auto& p : *list)
      top = std::max(top, p.z);
  return top;
}

void drawPolyline(
    cv::Mat& img, const TSnapshotView& view, const std::vector<TPoint3D>& pts,
    const cv::Point& offset, const cv::Scalar& colour, int thickness)
{
  std::vector<cv::Point> line;
  auto flush = [&]()
  {
    if (line.size() > 1)
      cv::polylines(img, line, false, colour, thickness, cv::LINE_AA);
    line.clear();
  };
  for (const auto& p : pts)
  {
    const auto px = view.project(p);
    if (!px)
    {
      flush();
      continue;
    }
    line.emplace_back(
        static_cast<int>(std::lround(px->x)) + offset.x,
        static_cast<int>(std::lround(px->y)) + offset.y);
  }
  flush();
}

void drawOverlays(
    cv::Mat& img, const TSnapshotView& view, const TSceneContent& c, const cv::Point& offset,
    const CSnapshotRenderer::TOptions& o)
{
  // The ground truth wider, under the estimate: both stay visible where they agree.
  drawPolyline(img, view, c.groundTruth, offset, kGroundTruthColour, o.trajectoryPx + 4);
  drawPolyline(img, view, c.trajectory, offset, kEstimateColour, o.trajectoryPx);
  // Keyframes that would overlap a mark already drawn are not marked again:
  // a cluster of marks would hide the trajectory under it.
  std::vector<cv::Point> marked;
  for (const auto& k : c.keyframes)
    if (const auto px = view.project(k))
    {
      const cv::Point pt(
          static_cast<int>(std::lround(px->x)) + offset.x,
          static_cast<int>(std::lround(px->y)) + offset.y);
      const bool overlaps = std::any_of(
          marked.begin(), marked.end(),
          [&](const cv::Point& m) { return cv::norm(m - pt) < 1.5 * o.keyframePx; });
      if (overlaps)
        continue;
      marked.push_back(pt);
      cv::circle(img, pt, o.keyframePx, kKeyframeColour, cv::FILLED, cv::LINE_AA);
      cv::circle(img, pt, o.keyframePx, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
    }
}

/** The legend in one line along the header strip: the text lines, then a
 *  sample of each drawn item, then the grid spacing. */
void drawLegend(
    cv::Mat& img, const TSceneContent& c, double gridSpacing, int thickness, int headerPx)
{
  const double scale = 0.55;
  const int mid = headerPx / 2, swatch = 30, gap = 26;
  int x = 10;
  auto text = [&](const std::string& t)
  {
    int base = 0;
    const auto sz = cv::getTextSize(t, kFont, scale, 1, &base);
    cv::putText(img, t, {x, mid + sz.height / 2}, kFont, scale, kTextColour, 1, cv::LINE_AA);
    x += sz.width + gap;
  };
  for (const auto& l : c.legend)
    text(l);
  if (c.groundTruth.size() > 1)
  {
    cv::line(img, {x, mid}, {x + swatch, mid}, kGroundTruthColour, thickness + 4, cv::LINE_AA);
    x += swatch + 6;
    text("ground truth");
  }
  if (c.trajectory.size() > 1)
  {
    cv::line(img, {x, mid}, {x + swatch, mid}, kEstimateColour, thickness, cv::LINE_AA);
    x += swatch + 6;
    text("estimate");
  }
  if (!c.keyframes.empty())
  {
    cv::circle(img, {x + 5, mid}, 4, kKeyframeColour, cv::FILLED, cv::LINE_AA);
    x += 16;
    text("keyframes (" + std::to_string(c.keyframes.size()) + ")");
  }
  char grid[64];
  std::snprintf(grid, sizeof grid, "grid %g m", gridSpacing);
  text(grid);
  cv::line(img, {0, headerPx - 1}, {img.cols, headerPx - 1}, cv::Scalar(200, 200, 200), 1);
}

/** A bar of one grid spacing at the bottom left of the top view. */
void drawScaleBar(cv::Mat& img, const TSnapshotView& view, const cv::Point& offset, double spacing)
{
  const int len = static_cast<int>(std::lround(view.pixelsPerMetre * spacing));
  if (len < 10 || len > static_cast<int>(view.camera.ncols) / 2)
    return;
  const int x0 = offset.x + 16, y0 = offset.y + static_cast<int>(view.camera.nrows) - 18;
  cv::line(img, {x0, y0}, {x0 + len, y0}, kTextColour, 2);
  cv::line(img, {x0, y0 - 5}, {x0, y0 + 5}, kTextColour, 2);
  cv::line(img, {x0 + len, y0 - 5}, {x0 + len, y0 + 5}, kTextColour, 2);
  char text[32];
  std::snprintf(text, sizeof text, "%g m", spacing);
  cv::putText(img, text, {x0 + len + 8, y0 + 5}, kFont, 0.5, kTextColour, 1, cv::LINE_AA);
}

void drawCaption(cv::Mat& img, const std::string& text, const cv::Point& offset, int panelWidth)
{
  int base = 0;
  const auto sz = cv::getTextSize(text, kFont, 0.6, 1, &base);
  const cv::Point at(offset.x + panelWidth - sz.width - 10, offset.y + 22);
  cv::rectangle(
      img, at + cv::Point(-5, -sz.height - 5), at + cv::Point(sz.width + 5, base + 3),
      cv::Scalar(255, 255, 255), cv::FILLED);
  cv::putText(img, text, at, kFont, 0.6, kTextColour, 1, cv::LINE_AA);
}
}  // namespace

unsigned int CSnapshotRenderer::panelWidth() const
{
  return m_options.topView ? m_options.width / 2 : m_options.width;
}

unsigned int CSnapshotRenderer::headerHeight() const
{
  return m_options.overlays ? std::min(m_options.headerPx, m_options.height / 2) : 0;
}

unsigned int CSnapshotRenderer::panelHeight() const
{
  return m_options.height - headerHeight();
}

std::vector<TSnapshotView> CSnapshotRenderer::views(const TSceneContent& content) const
{
  const auto box = robustBounds(content, m_options.framingQuantile);
  if (!box)
    return {};
  const CViewFramer framer(m_options.framing);
  const auto pts = framingPoints(content, *box);
  const auto heading = framer.heading(content.lookDirection);
  std::vector<TSnapshotView> v{framer.perspective(pts, *box, heading, panelWidth(), panelHeight())};
  if (m_options.topView)
    v.push_back(framer.topDown(pts, *box, heading, panelWidth(), panelHeight()));
  return v;
}

mrpt::img::CImage CSnapshotRenderer::render(const TSceneContent& content) const
{
  const unsigned W = panelWidth(), H = panelHeight();
  const int header = static_cast<int>(headerHeight());
  const int bg = static_cast<int>(std::lround(255 * std::clamp(m_options.background, 0.f, 1.f)));
  cv::Mat out(
      static_cast<int>(m_options.height), static_cast<int>(m_options.width), CV_8UC3,
      cv::Scalar(bg, bg, bg));
  const auto views = this->views(content);
  const CSlamSceneBuilder grid;
  const double spacing = grid.gridSpacing(content);
  try
  {
    if (!views.empty())
    {
      mrpt::opengl::CFBORender fbo(W, H);
      for (std::size_t k = 0; k < views.size(); ++k)
      {
        const auto& view = views[k];
        CSlamSceneBuilder::TOptions so;
        so.showTrajectories = !m_options.overlays;
        // Points about 1.5 cm across (the map's spacing at 1-2 m with
        // [BackEnd] map_decimation 8): surfaces look solid, at 2-6 px.
        so.pointSize = static_cast<float>(std::clamp(0.015 * view.pixelsPerMetre, 2.0, 6.0));
        const double top = highestCamera(content);
        if (k == 1 && std::isfinite(top))
          so.maxPointHeight = top + m_options.cutAboveCamerasM;
        auto scene = CSlamSceneBuilder(so).build(content);
        auto viewport = scene->getViewport("main");
        const float g = m_options.background;
        viewport->setCustomBackgroundColor(mrpt::img::TColorf(g, g, g));
        viewport->setViewportClipDistances(
            static_cast<float>(view.nearM), static_cast<float>(view.farM));
        mrpt::opengl::CCamera camera;
        camera.set6DOFMode(true);
        camera.setPose(view.pose);
        camera.setProjectiveFromPinhole(view.camera);
        fbo.setCamera(*scene, camera);
        mrpt::img::CImage img;
        fbo.render_RGB(*scene, img);
        img.asCvMatRef().copyTo(out(
            cv::Rect(static_cast<int>(k * W), header, static_cast<int>(W), static_cast<int>(H))));
      }
    }
  }
  catch (const std::exception& e)
  {
    // MRPT exceptions span several lines; keep the first one.
    std::string what = e.what();
    what = what.substr(0, what.find('\n'));
    throw std::runtime_error("offscreen rendering failed: " + what);
  }
  if (m_options.overlays && !views.empty())
  {
    const cv::Point left(0, header), right(static_cast<int>(W), header);
    drawOverlays(out, views[0], content, left, m_options);
    drawCaption(out, "3-D view", left, static_cast<int>(W));
    if (views.size() > 1)
    {
      drawOverlays(out, views[1], content, right, m_options);
      cv::line(out, right, {right.x, out.rows}, cv::Scalar(200, 200, 200), 1);
      drawCaption(out, "top view", right, static_cast<int>(W));
      drawScaleBar(out, views[1], right, spacing);
    }
    drawLegend(out, content, spacing, m_options.trajectoryPx, header);
  }
  return mrpt::img::CImage(out, mrpt::img::DEEP_COPY);
}

void CSnapshotRenderer::renderToFile(const TSceneContent& content, const std::string& pngFile) const
{
  const auto image = render(content);
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
