/* CLiveView::TImpl's drawing thread (LiveViewImpl.h): it takes the queued
 * updates at most as often as the redraw budget allows, puts them into the
 * scene and the image viewports, writes the status texts, moves the camera
 * while it follows the map, and asks MRPT's wx thread to repaint. Started
 * by TImpl's constructor; repaint() is also called by capture().
 */
#include <pthread.h>
#include <roislam/gui/FrameOverlay.h>
#include <roislam/viz/CViewFramer.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <opencv2/imgproc.hpp>

#include "LiveViewImpl.h"
#include "WxRefresh.h"

namespace roislam::gui
{
using detail::kElevationDeg;
using detail::kViewThreads;
using detail::secondsSince;

namespace
{
/** `img` shrunk to fit `size` (aspect kept); never enlarged. */
cv::Mat fitTo(const cv::Mat& img, const cv::Size& size)
{
  if (img.empty())
    return img;
  const double s = std::min(
      {1.0, size.width / static_cast<double>(img.cols),
       size.height / static_cast<double>(img.rows)});
  if (s >= 1.0)
    return img;
  cv::Mat out;
  cv::resize(img, out, cv::Size(), s, s, cv::INTER_AREA);
  return out;
}
}  // namespace

void CLiveView::TImpl::drawLoop()
{
  pthread_setname_np(pthread_self(), "roislam-view");
  for (;;)
  {
    const auto step = std::chrono::duration<double>(budget.period());
    std::vector<TUpdate> updates;
    std::optional<TShot> shot;
    std::string shotDir;
    {
      std::unique_lock<std::mutex> lk(mutex);
      wake.wait_for(lk, step, [this] { return stopDrawing || !shots.empty(); });
      if (stopDrawing)
        return;
      shotDir = session.screenshotDir;  // onOutputFolder() moves it
      updates.swap(pending);
      sequenceShown = sequence;
      messageShown = message;
      if (!shots.empty())
      {
        shot = shots.front();
        shots.pop_front();
      }
    }
    const double now = secondsSince(start);
    const bool flashing = scene->flashingClosures(now) > 0 || gliding;
    if (!updates.empty() || statusDirty.exchange(false) || flashing || shot)
    {
      draw(updates);
      ++redraws;
      const auto [viewCpu, processCpu] = threadCpuSeconds(kViewThreads);
      budget.update(viewCpu, processCpu);
    }
    for (std::size_t n = keyShots.exchange(0); n > 0; --n)
    {
      char name[64];
      std::snprintf(name, sizeof(name), "screenshot-%06zu.png", last ? last->index : 0);
      serve({(std::filesystem::path(shotDir) / name).string(), nullptr});
    }
    if (shot)
      serve(*shot);
  }
}

void CLiveView::TImpl::applyUpdates(std::vector<TUpdate>& updates, double now)
{
  for (auto& u : updates)
  {
    if (u.groundTruth)
      scene->setGroundTruth(std::move(*u.groundTruth));
    if (u.keyframePoses)
      scene->setKeyframePoses(*u.keyframePoses, u.loops, now);
    if (!u.frame)
      continue;
    scene->addFrame(*u.frame, now);
    ++framesSeen;
    u.frame->cloud.reset();  // in the scene now
    if (!u.frame->rgb.empty())
      shown = *u.frame;  // shares the images
    last = std::move(u.frame);
  }
  // fps over the last seconds of frames, as the SLAM thread processed them.
  if (last)
    rate.emplace_back(last->processedAt, framesSeen);
  while (rate.size() > 2 && rate.back().first - rate.front().first > 3.0)
    rate.pop_front();
}

void CLiveView::TImpl::draw(std::vector<TUpdate>& updates)
{
  const double now = secondsSince(start);
  bool newImage = false;
  for (const auto& u : updates)
    newImage = newImage || (u.frame && !u.frame->rgb.empty());
  applyUpdates(updates, now);
  cv::Mat overlay, depth;
  if (newImage && shown)
  {
    // At the viewports' size: the texture upload is the costly part of a
    // redraw under software GL (2 x 640 x 480: 9 ms of 31 per redraw).
    const cv::Size size(static_cast<int>(std::lround(options.width * column)), options.height / 2);
    overlay = fitTo(drawFrameOverlay(*shown, roiMode), size);
    depth = fitTo(colouriseDepth(shown->depth, options.max_depth_m), size);
  }
  {
    mrpt::opengl::COpenGLScene::Ptr sc;
    mrpt::gui::CDisplayWindow3DLocker lock(*win, sc);
    scene->update(*mainView, now);
    if (!overlay.empty())
      colourView->setImageView(mrpt::img::CImage(overlay, mrpt::img::SHALLOW_COPY));
    if (!depth.empty())
      depthView->setImageView(mrpt::img::CImage(depth, mrpt::img::SHALLOW_COPY));
    updateTexts();
  }
  follow();
  repaint();
}

void CLiveView::TImpl::repaint()
{
#if ROISLAM_GUI_WX_HEADERS
  auto* w = win.get();
  win->sendFunctionToRunOnGUIThread([w] { detail::refreshChildren(w->getWxObject()); });
#else
  win->forceRepaint();
#endif
}

void CLiveView::TImpl::updateTexts()
{
  mrpt::opengl::TFontParams font;
  font.vfont_scale = 10.5f;
  font.draw_shadow = true;
  char line[256];
  double fps = 0;
  if (rate.size() >= 2 && rate.back().first > rate.front().first)
    fps = (rate.back().second - rate.front().second) / (rate.back().first - rate.front().first);
  const char* paused = isPaused ? "  PAUSED" : "";
  if (last)
    std::snprintf(
        line, sizeof(line), "frame %zu  %.1f fps  keyframes %zu  closures %zu  fallbacks %zu%s%s",
        last->index + 1, fps, last->keyframes, last->loopClosures, last->fallbackFrames,
        last->lostFrames ? ("  lost " + std::to_string(last->lostFrames)).c_str() : "", paused);
  else
    std::snprintf(line, sizeof(line), "waiting for the first frame%s", paused);
  mainView->addTextMessage(8, 24, line, 0, font);
  mrpt::opengl::TFontParams small = font;
  small.vfont_scale = 9;
  small.color = {0.8f, 0.8f, 0.8f, 1.f};
  char help[128];
  std::snprintf(
      help, sizeof(help), "space pause  s screenshot  q quit  f follow   (view %.1f Hz)",
      1.0 / budget.period());
  mainView->addTextMessage(8, 8, messageShown.empty() ? std::string(help) : messageShown, 1, small);
  mainView->addTextMessage(
      8, -30, "blue: estimate  green: ground truth  red: closures (new yellow)", 2, small);
  small.color = {1.f, 1.f, 1.f, 1.f};
  mainView->addTextMessage(8, -16, sequenceShown, 3, small);
}

// ---- the following camera -----------------------------------------------------

void CLiveView::TImpl::follow()
{
  if (!following)
    return;
  // The user moved the camera (mouse drag or wheel) since we set it:
  // leave it to them until 'f'.
  if (orbitSet && cameraMovedByUser())
  {
    following = false;
    orbitSet.reset();
    return;
  }
  if (const auto target = orbitTarget())
    glideTo(*target);
}

bool CLiveView::TImpl::cameraMovedByUser() const
{
  float x, y, z;
  win->getCameraPointingToPoint(x, y, z);
  const float dz = std::abs(win->getCameraZoom() - orbitSet->zoom);
  const float da =
      std::abs(std::remainder(win->getCameraAzimuthDeg() - orbitSet->azimuthDeg, 360.f));
  const float de = std::abs(win->getCameraElevationDeg() - orbitSet->elevationDeg);
  const float dp =
      std::abs(x - orbitSet->x) + std::abs(y - orbitSet->y) + std::abs(z - orbitSet->z);
  return dz > 1e-3f || da > 1e-2f || de > 1e-2f || dp > 1e-3f;
}

std::optional<CLiveView::TImpl::TOrbit> CLiveView::TImpl::orbitTarget() const
{
  const auto box = scene->bounds();
  if (!box)
    return std::nullopt;
  const auto centre = (box->min + box->max) * 0.5;
  const auto half = (box->max - box->min) * 0.5;
  const double zoom = std::max(1.0, 2.2 * half.norm());
  const auto h = viz::CViewFramer().heading(scene->lookDirection());
  return TOrbit{
      static_cast<float>(centre.x),
      static_cast<float>(centre.y),
      static_cast<float>(centre.z),
      static_cast<float>(zoom),
      static_cast<float>(std::atan2(-h.y, -h.x) * 180 / M_PI),
      kElevationDeg};
}

void CLiveView::TImpl::glideTo(const TOrbit& target)
{
  // Glide there rather than jump at each new keyframe.
  TOrbit o = orbitSet.value_or(target);
  const float a = 0.35f;
  o.x += a * (target.x - o.x);
  o.y += a * (target.y - o.y);
  o.z += a * (target.z - o.z);
  o.zoom += a * (target.zoom - o.zoom);
  float dAz = std::remainder(target.azimuthDeg - o.azimuthDeg, 360.f);
  o.azimuthDeg += a * dAz;
  gliding = std::abs(target.zoom - o.zoom) > 0.01f * target.zoom || std::abs(dAz) > 0.5f ||
            std::abs(target.x - o.x) + std::abs(target.y - o.y) > 0.01f * target.zoom;
  win->setCameraPointingToPoint(o.x, o.y, o.z);
  win->setCameraZoom(o.zoom);
  win->setCameraAzimuthDeg(o.azimuthDeg);
  win->setCameraElevationDeg(o.elevationDeg);
  orbitSet = o;
}
}  // namespace roislam::gui
