/* CLiveView::TImpl's window and lifecycle (LiveViewImpl.h): it opens the
 * window and its three viewports, starts and stops the drawing thread,
 * handles MRPT's window events and keys (on MRPT's wx thread) and takes
 * the SLAM thread's updates into the queue. Called by CLiveView's methods
 * and MRPT's wx thread.
 */
#include "LiveViewImpl.h"

#include <roislam/gui/X11Display.h>

#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace roislam::gui
{
using detail::kElevationDeg;
using detail::kMaxPeriodS;
using detail::kViewThreads;
using detail::secondsSince;

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
}  // namespace roislam::gui
