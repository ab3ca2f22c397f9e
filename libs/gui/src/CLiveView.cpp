#include "roislam/gui/CLiveView.h"

#include <mrpt/gui/CDisplayWindow3D.h>
#include <mrpt/system/CObserver.h>
#include <pthread.h>
#include <roislam/common/CStrictIniFile.h>
#include <roislam/common/IniKeyCheck.h>
#include <roislam/common/IniRead.h>
#include <roislam/common/TextFiles.h>
#include <roislam/gui/CLiveScene.h>
#include <roislam/gui/CRedrawBudget.h>
#include <roislam/gui/FrameOverlay.h>
#include <roislam/gui/TLiveFrame.h>
#include <roislam/gui/X11Display.h>
#include <roislam/io/TumTrajectory.h>
#include <roislam/viz/CViewFramer.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <future>
#include <iostream>
#include <mutex>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <thread>

#include "WxRefresh.h"

namespace roislam::gui
{
namespace
{
constexpr const char* kSection = "LiveView";
/** The 3-D view looks down by this much (deg): steeper than the snapshot's
 *  40, so that the path and its closures show inside the map. */
constexpr float kElevationDeg = 55.f;
/** The view redraws at least this often (s), whatever the budget says. */
constexpr double kMaxPeriodS = 3.0;
/** Threads whose CPU counts as the view's (CRedrawBudget): ours, MRPT's wx
 *  thread and those GTK and Mesa start from it or for it (llvmpipe, its
 *  disk cache thread, named after the process). */
const std::vector<std::string> kViewThreads = {"roislam-view", "wxMainThread", "llvmpipe", "gmain",
                                               "gdbus",        "pool-",        ":disk$"};
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t0)
{
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

/** What the SLAM thread hands to the drawing thread, in order. */
struct TUpdate
{
  std::optional<TLiveFrame> frame;
  std::optional<std::map<std::size_t, mrpt::poses::CPose3D>> keyframePoses;
  std::vector<std::pair<std::size_t, std::size_t>> loops;
  std::optional<io::TTrajectory> groundTruth;
};

/** A screenshot asked for by saveScreenshot() or the 's' key. */
struct TShot
{
  std::string file;
  std::shared_ptr<std::promise<void>> done;  // null for the key
};

/** The main view's orbit camera, as set by follow mode. */
struct TOrbit
{
  float x = 0, y = 0, z = 0, zoom = 5, azimuthDeg = 0, elevationDeg = kElevationDeg;
};

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

/** A captured window is real when it is not one colour (MRPT's own capture
 *  gives black where the front buffer cannot be read back). */
bool hasContent(const cv::Mat& img)
{
  if (img.empty())
    return false;
  double lo[3], hi[3];
  std::vector<cv::Mat> ch;
  cv::split(img, ch);
  for (std::size_t c = 0; c < ch.size(); ++c)
  {
    cv::minMaxLoc(ch[c], &lo[c], &hi[c]);
    if (hi[c] > lo[c])
      return true;
  }
  return false;
}
}  // namespace

// ---- options ----------------------------------------------------------------

void CLiveView::TOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& s)
{
  refresh_hz = common::readDouble(c, s, "refresh_hz", refresh_hz);
  max_cpu_share = common::readDouble(c, s, "max_cpu_share", max_cpu_share);
  width = common::readInt(c, s, "width", width);
  height = common::readInt(c, s, "height", height);
  map_points_per_keyframe =
      common::readInt(c, s, "map_points_per_keyframe", map_points_per_keyframe);
  point_size_px = common::readDouble(c, s, "point_size_px", point_size_px);
  flash_s = common::readDouble(c, s, "flash_s", flash_s);
  max_depth_m = common::readDouble(c, s, "max_depth_m", max_depth_m);
  follow = common::readBool(c, s, "follow", follow);
  validate();
}

void CLiveView::TOptions::saveToConfigFile(
    mrpt::config::CConfigFileBase& c, const std::string& s) const
{
  c.write(s, "refresh_hz", refresh_hz);
  c.write(s, "max_cpu_share", max_cpu_share);
  c.write(s, "width", width);
  c.write(s, "height", height);
  c.write(s, "map_points_per_keyframe", map_points_per_keyframe);
  c.write(s, "point_size_px", point_size_px);
  c.write(s, "flash_s", flash_s);
  c.write(s, "max_depth_m", max_depth_m);
  c.write(s, "follow", follow);
}

void CLiveView::TOptions::validate() const
{
  common::require(
      refresh_hz >= 0.5 && refresh_hz <= 60, kSection, "refresh_hz", refresh_hz, "in [0.5, 60]");
  common::require(
      max_cpu_share > 0 && max_cpu_share <= 1, kSection, "max_cpu_share", max_cpu_share,
      "in (0, 1]");
  common::require(width >= 320, kSection, "width", width, ">= 320");
  common::require(height >= 240, kSection, "height", height, ">= 240");
  common::require(
      map_points_per_keyframe >= 1, kSection, "map_points_per_keyframe", map_points_per_keyframe,
      ">= 1");
  common::require(point_size_px > 0, kSection, "point_size_px", point_size_px, "> 0");
  common::require(flash_s >= 0, kSection, "flash_s", flash_s, ">= 0");
  common::require(max_depth_m > 0, kSection, "max_depth_m", max_depth_m, "> 0");
}

CLiveView::TOptions CLiveView::loadOptions(const std::string& iniFile)
{
  TOptions o;
  if (iniFile.empty())
    return o;
  const common::CStrictIniFile cfg(iniFile);  // syntax checked: file:line errors
  common::checkIniKeys(cfg, kSection, common::knownIniKeys(o, kSection), iniFile);
  o.loadFromConfigFile(cfg, kSection);
  return o;
}

// ---- implementation -----------------------------------------------------------

struct CLiveView::TImpl : public mrpt::system::CObserver
{
  TImpl(const TOptions& o, TSession s);
  ~TImpl() override;

  void OnEvent(const mrpt::system::mrptEvent& e) override;
  void onKey(int key);
  void push(TUpdate u);
  void waitWhilePaused();
  void drawLoop();
  void draw(std::vector<TUpdate>& updates);
  void applyUpdates(std::vector<TUpdate>& updates, double now);
  void updateTexts();
  void follow();
  /** One repaint of the canvas (WxRefresh.h). */
  void repaint();
  /** Drops our references to the scene's objects and clears the scene on
   *  MRPT's GUI thread, so that every OpenGL object is destroyed there,
   *  now, and none when the window's deferred deletion runs during the
   *  process's exit (which raced MRPT's static texture handler: "free():
   *  invalid pointer" in 2 of 18 parallel runs). */
  void releaseScene();
  /** "live view: N redraws in T s, its threads X s of CPU (Y % of the
   *  rest of the process's)". */
  std::string summaryLine() const;
  cv::Mat capture();
  void serve(const TShot& shot);
  /** Notifies after taking the mutex once, so that a waiter that has just
   *  checked its condition cannot miss it. */
  void notify(std::condition_variable& cv)
  {
    {
      std::lock_guard<std::mutex> lk(mutex);
    }
    cv.notify_all();
  }
  void setMessageFromGui(const std::string& text)
  {
    {
      std::lock_guard<std::mutex> lk(mutex);
      message = text;
    }
    statusDirty = true;
  }
  void log(const std::string& line) const
  {
    if (session.log)
      session.log(session.appName + ": " + line);
  }

  TOptions options;
  TSession session;
  Clock::time_point start = Clock::now();
  double period;
  CRedrawBudget budget;
  /** Width of the image column, fraction of the window. */
  double column = 0.375;
  mrpt::gui::CDisplayWindow3D::Ptr win;
  mrpt::opengl::COpenGLViewport::Ptr mainView, colourView, depthView;
  std::unique_ptr<CLiveScene> scene;
  bool roiMode = false;

  // Shared between threads (mutex): the queue, requests, stop flags.
  mutable std::mutex mutex;
  std::condition_variable wake;     // drawing thread
  std::condition_variable resumed;  // SLAM thread, while paused
  std::condition_variable closed;   // waitUntilClosed()
  std::vector<TUpdate> pending;
  std::deque<TShot> shots;
  bool stopDrawing = false;
  std::string message;
  std::atomic<bool> quit{false}, isPaused{false}, statusDirty{true}, following{true};
  std::atomic<std::size_t> keyShots{0};

  // SLAM thread only.
  double lastImageAt = -1e9;
  std::size_t loopsSeen = 0;

  // Shared (mutex): set by the app thread, shown by the drawing thread.
  std::string sequence;

  // Drawing thread only.
  std::optional<TLiveFrame> last;                   // the newest frame (its counts)
  std::optional<TLiveFrame> shown;                  // the newest frame with an image
  std::deque<std::pair<double, std::size_t>> rate;  // (time, frames) for fps
  std::size_t framesSeen = 0;
  std::string sequenceShown, messageShown;
  std::optional<TOrbit> orbitSet;
  bool gliding = false;
  std::size_t redraws = 0;

  std::thread drawer;
};

CLiveView::TImpl::TImpl(const TOptions& o, TSession s)
    : options(o),
      session(std::move(s)),
      period(1.0 / o.refresh_hz),
      budget(1.0 / o.refresh_hz, kMaxPeriodS, o.max_cpu_share),
      scene(std::make_unique<CLiveScene>(
          CLiveScene::TOptions{static_cast<float>(o.point_size_px), o.flash_s, 100}))
{
  options.validate();
  const auto display = requireX11Display();  // held until the window has connected
  // One X display is what --gui needs (and what the screenshots read);
  // GTK on Wayland would give no X window.
  setenv("GDK_BACKEND", "x11", 0);
  isPaused = session.startPaused;
  following = options.follow;
  win = mrpt::gui::CDisplayWindow3D::Create(
      session.appName + " live view", static_cast<unsigned>(options.width),
      static_cast<unsigned>(options.height));
  if (!win->wait_for_GL_context(10.0) || !win->isOpen())
    throw std::runtime_error("--gui: cannot create an OpenGL window on this display");
  // Right column: the colour image above the depth image, each 4:3 at half
  // the window's height; the 3-D view fills the rest.
  column = std::min(0.5, (options.height / 2.0) * 4.0 / 3.0 / static_cast<double>(options.width));
  {
    mrpt::opengl::COpenGLScene::Ptr sc;
    mrpt::gui::CDisplayWindow3DLocker lock(*win, sc);
    mainView = sc->getViewport("main");
    mainView->setViewportPosition(0, 0, 1 - column, 1);
    mainView->setCustomBackgroundColor({0.1f, 0.1f, 0.12f});
    colourView = sc->createViewport("colour");
    colourView->setViewportPosition(1 - column, 0.5, column, 0.5);
    depthView = sc->createViewport("depth");
    depthView->setViewportPosition(1 - column, 0, column, 0.5);
    for (auto* v : {colourView.get(), depthView.get()})
    {
      v->setCustomBackgroundColor({0, 0, 0});
      v->setBorderSize(1);
    }
    scene->update(*mainView, 0);
  }
  win->setCameraElevationDeg(kElevationDeg);
  win->setCameraZoom(5);
  observeBegin(*win);
  drawer = std::thread([this] { drawLoop(); });
}

CLiveView::TImpl::~TImpl()
{
  {
    std::lock_guard<std::mutex> lk(mutex);
    stopDrawing = true;
    quit = true;
  }
  wake.notify_all();
  resumed.notify_all();
  closed.notify_all();
  if (drawer.joinable())
    drawer.join();
  log(summaryLine());
  if (win)
  {
    observeEnd(*win);
    releaseScene();
  }
  for (auto& s : shots)
    if (s.done)
      s.done->set_exception(std::make_exception_ptr(std::runtime_error("live view closed")));
}

std::string CLiveView::TImpl::summaryLine() const
{
  const auto [viewCpu, processCpu] = threadCpuSeconds(kViewThreads);
  char line[200];
  std::snprintf(
      line, sizeof(line),
      "live view: %zu redraws in %.1f s, its threads %.2f s of CPU (%.1f %% of the rest)", redraws,
      secondsSince(start), viewCpu,
      processCpu > viewCpu ? 100.0 * viewCpu / (processCpu - viewCpu) : 0.0);
  return line;
}

void CLiveView::TImpl::releaseScene()
{
  scene.reset();
  mainView.reset();
  colourView.reset();
  depthView.reset();
  if (!win->isOpen())
    return;
  auto done = std::make_shared<std::promise<void>>();
  auto cleared = done->get_future();
  auto* w = win.get();
  win->sendFunctionToRunOnGUIThread(
      [w, done]
      {
        {
          mrpt::opengl::COpenGLScene::Ptr sc;
          mrpt::gui::CDisplayWindow3DLocker lock(*w, sc);
          sc->clear(true);
        }
        done->set_value();
      });
  if (cleared.wait_for(std::chrono::seconds(5)) != std::future_status::ready)
    log("warning: the window did not answer; closing it anyway");
}

void CLiveView::TImpl::OnEvent(const mrpt::system::mrptEvent& e)
{
  // MRPT's wx thread: flags and notifications only.
  if (e.isOfType<mrpt::gui::mrptEventWindowChar>())
    onKey(static_cast<const mrpt::gui::mrptEventWindowChar&>(e).char_code);
  else if (e.isOfType<mrpt::gui::mrptEventWindowClosed>())
  {
    // The window stays until the run has written its outputs and this view
    // closes it (~TImpl): its objects must go on the GUI thread first. A
    // second close (the run not ending) is let through.
    if (!quit)
    {
      const_cast<mrpt::gui::mrptEventWindowClosed&>(
          static_cast<const mrpt::gui::mrptEventWindowClosed&>(e))
          .allow_close = false;
      log("window closed: stopping the run, writing the outputs");
      setMessageFromGui("stopping: writing the outputs...");
    }
    quit = true;
    notify(resumed);
    notify(closed);
  }
}

void CLiveView::TImpl::onKey(int key)
{
  if (key == ' ')
  {
    isPaused = !isPaused;
    log(isPaused ? "paused (space resumes)" : "resumed");
    notify(resumed);
  }
  else if (key == 'q' || key == 'Q')
  {
    if (!quit)
    {
      log("q: stopping the run, writing the outputs");
      setMessageFromGui("stopping: writing the outputs...");
    }
    quit = true;
    notify(resumed);
    notify(closed);
  }
  else if (key == 's' || key == 'S')
    ++keyShots;
  else if (key == 'f' || key == 'F')
    following = true;
  else
    return;
  statusDirty = true;
  notify(wake);
}

void CLiveView::TImpl::push(TUpdate u)
{
  {
    std::lock_guard<std::mutex> lk(mutex);
    // Only the newest image is ever shown: older queued ones go.
    if (u.frame && !u.frame->rgb.empty())
      for (auto& p : pending)
        if (p.frame)
        {
          p.frame->rgb.release();
          p.frame->depth.release();
          p.frame->featurePixels.clear();
        }
    pending.push_back(std::move(u));
  }
}

void CLiveView::TImpl::waitWhilePaused()
{
  if (!isPaused || quit)
    return;
  wake.notify_all();  // show the paused state at once
  std::unique_lock<std::mutex> lk(mutex);
  resumed.wait(lk, [this] { return !isPaused || quit; });
}

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

void CLiveView::TImpl::follow()
{
  if (!following)
    return;
  // The user moved the camera (mouse drag or wheel) since we set it:
  // leave it to them until 'f'.
  if (orbitSet)
  {
    float x, y, z;
    win->getCameraPointingToPoint(x, y, z);
    const float dz = std::abs(win->getCameraZoom() - orbitSet->zoom);
    const float da =
        std::abs(std::remainder(win->getCameraAzimuthDeg() - orbitSet->azimuthDeg, 360.f));
    const float de = std::abs(win->getCameraElevationDeg() - orbitSet->elevationDeg);
    const float dp =
        std::abs(x - orbitSet->x) + std::abs(y - orbitSet->y) + std::abs(z - orbitSet->z);
    if (dz > 1e-3f || da > 1e-2f || de > 1e-2f || dp > 1e-3f)
    {
      following = false;
      orbitSet.reset();
      return;
    }
  }
  const auto box = scene->bounds();
  if (!box)
    return;
  const auto centre = (box->min + box->max) * 0.5;
  const auto half = (box->max - box->min) * 0.5;
  const double zoom = std::max(1.0, 2.2 * half.norm());
  const auto h = viz::CViewFramer().heading(scene->lookDirection());
  TOrbit target{
      static_cast<float>(centre.x),
      static_cast<float>(centre.y),
      static_cast<float>(centre.z),
      static_cast<float>(zoom),
      static_cast<float>(std::atan2(-h.y, -h.x) * 180 / M_PI),
      kElevationDeg};
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

cv::Mat CLiveView::TImpl::capture()
{
  if (!win->isOpen())
    throw std::runtime_error("the window is closed");
  // Wait for two paints that started after the scene was updated: MRPT
  // stores a new image at each paint while capturing.
  win->captureImagesStart();
  auto previous = win->getLastWindowImagePtr();
  for (int paints = 0, tries = 0; paints < 2 && tries < 250; ++tries)
  {
    if (tries % 25 == 0)
      repaint();
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    const auto now = win->getLastWindowImagePtr();
    if (now && now != previous)
    {
      ++paints;
      previous = now;
      repaint();
    }
  }
  win->captureImagesStop();
  if (previous)
  {
    cv::Mat mrptImage = previous->asCvMat<cv::Mat>(mrpt::img::DEEP_COPY);
    if (hasContent(mrptImage))
      return mrptImage;
  }
  // MRPT's read-back came out black: the front buffer is not readable
  // (Mesa's software GLX, e.g. under Xvfb). The X server has the pixels.
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  if (auto x = captureOwnWindow())
    return *x;
  throw std::runtime_error("cannot read the window back");
}

void CLiveView::TImpl::serve(const TShot& shot)
{
  try
  {
    const cv::Mat img = capture();
    std::vector<uchar> png;
    if (!cv::imencode(".png", img, png))
      throw std::runtime_error("PNG encoding failed");
    const auto dir = std::filesystem::path(shot.file).parent_path();
    if (!dir.empty())
      std::filesystem::create_directories(dir);
    common::writeFileAtomically(shot.file, std::string(png.begin(), png.end()));
    if (shot.done)
      shot.done->set_value();
    else
      log("screenshot " + shot.file);
  }
  catch (const std::exception& e)
  {
    const std::string what = e.what();
    if (shot.done)
      shot.done->set_exception(std::make_exception_ptr(
          std::runtime_error("screenshot " + shot.file + ": " + what.substr(0, what.find('\n')))));
    else
      log("warning: screenshot " + shot.file + ": " + what.substr(0, what.find('\n')));
  }
}

// ---- CLiveView ----------------------------------------------------------------

CLiveView::CLiveView(const TOptions& options, TSession session)
    : m_impl(std::make_unique<TImpl>(options, std::move(session)))
{
}

CLiveView::~CLiveView() = default;

void CLiveView::onOutputFolder(const std::string& dir)
{
  std::lock_guard<std::mutex> lk(m_impl->mutex);
  m_impl->session.screenshotDir = dir;
}

void CLiveView::onStart(const io::CFrameSource& source, const graphslam::CSlamContext& context)
{
  m_impl->roiMode = frontend::isRoiMode(context.config().frontEnd.mode);
  TUpdate u;
  if (const auto gt = source.groundTruthFile(); gt && std::filesystem::exists(*gt))
  {
    try
    {
      u.groundTruth = io::loadTumTrajectory(*gt);
    }
    catch (const std::exception& e)
    {
      const std::string what = e.what();
      m_impl->log("warning: no ground truth in the view: " + what.substr(0, what.find('\n')));
    }
  }
  {
    std::lock_guard<std::mutex> lk(m_impl->mutex);
    m_impl->sequence = source.name() + ", " + frontend::toString(context.config().frontEnd.mode) +
                       ", " + features::toString(context.config().frontEnd.extractor.feature_type);
  }
  m_impl->win->setWindowTitle(m_impl->session.appName + ": " + source.name());
  m_impl->push(std::move(u));
  m_impl->statusDirty = true;
  m_impl->notify(m_impl->wake);
}

void CLiveView::onFrame(
    const frontend::TFrameResult& result, const io::TRGBDFrame& frame,
    const graphslam::CSlamContext& context)
{
  TImpl& I = *m_impl;
  const double now = secondsSince(I.start);
  const bool withImage = now - I.lastImageAt >= 0.999 * I.period;
  if (withImage)
    I.lastImageAt = now;
  TUpdate u;
  u.frame = makeLiveFrame(
      result, frame, context, withImage,
      static_cast<std::size_t>(I.options.map_points_per_keyframe), I.loopsSeen);
  u.frame->processedAt = now;
  I.loopsSeen = u.frame->loopClosures;
  I.push(std::move(u));
  I.waitWhilePaused();
}

void CLiveView::onOptimized(const graphslam::TGraph& graph, const graphslam::CSlamContext& context)
{
  TUpdate u;
  u.keyframePoses.emplace();
  for (const auto& [id, pose] : graph.nodes)
    (*u.keyframePoses)[id] = pose;
  u.loops = loopPairs(context);
  m_impl->loopsSeen = u.loops.size();
  m_impl->push(std::move(u));
}

bool CLiveView::stopRequested() const
{
  return m_impl->quit;
}

bool CLiveView::paused() const
{
  return m_impl->isPaused;
}

void CLiveView::saveScreenshot(const std::string& pngFile)
{
  auto done = std::make_shared<std::promise<void>>();
  auto result = done->get_future();
  {
    std::lock_guard<std::mutex> lk(m_impl->mutex);
    if (m_impl->stopDrawing)
      throw std::runtime_error("screenshot " + pngFile + ": the live view is closed");
    m_impl->shots.push_back({pngFile, done});
  }
  m_impl->wake.notify_all();
  result.get();
}

void CLiveView::setMessage(const std::string& text)
{
  {
    std::lock_guard<std::mutex> lk(m_impl->mutex);
    m_impl->message = text;
  }
  m_impl->statusDirty = true;
  m_impl->wake.notify_all();
}

void CLiveView::waitUntilClosed()
{
  std::unique_lock<std::mutex> lk(m_impl->mutex);
  m_impl->closed.wait(lk, [this] { return m_impl->quit.load(); });
}

void exitAfterLiveView(int code)
{
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
  std::_Exit(code);
}
}  // namespace roislam::gui
