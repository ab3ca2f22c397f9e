/* Private: CLiveView's implementation (CLiveView::TImpl), the state its
 * three threads share (the SLAM thread's queue, the drawing thread, MRPT's
 * wx thread) and the small types they hand each other. Defined in three
 * files by concern: LiveViewImpl.cpp (window, lifecycle, keys, the queue),
 * LiveViewDrawing.cpp (the drawing thread: redraws, status texts, the
 * following camera) and LiveViewScreenshot.cpp (window read-back, PNGs).
 * Included by those and by CLiveView.cpp only.
 */
#pragma once

#include <mrpt/gui/CDisplayWindow3D.h>
#include <mrpt/system/CObserver.h>
#include <roislam/gui/CLiveScene.h>
#include <roislam/gui/CLiveView.h>
#include <roislam/gui/CRedrawBudget.h>
#include <roislam/gui/TLiveFrame.h>
#include <roislam/io/TumTrajectory.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace roislam::gui
{
namespace detail
{
/** The 3-D view looks down by this much (deg): steeper than the snapshot's
 *  40, so that the path and its closures show inside the map. */
inline constexpr float kElevationDeg = 55.f;
/** The view redraws at least this often (s), whatever the budget says. */
inline constexpr double kMaxPeriodS = 3.0;
/** Threads whose CPU counts as the view's (CRedrawBudget): ours, MRPT's wx
 *  thread and those GTK and Mesa start from it or for it (llvmpipe, its
 *  disk cache thread, named after the process). */
inline const std::vector<std::string> kViewThreads = {
    "roislam-view", "wxMainThread", "llvmpipe", "gmain", "gdbus", "pool-", ":disk$"};
using Clock = std::chrono::steady_clock;

inline double secondsSince(Clock::time_point t0)
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
}  // namespace detail

struct CLiveView::TImpl : public mrpt::system::CObserver
{
  using TUpdate = detail::TUpdate;
  using TShot = detail::TShot;
  using TOrbit = detail::TOrbit;
  using Clock = detail::Clock;

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
  /** Whether the camera is no longer where follow() last set it (orbitSet). */
  bool cameraMovedByUser() const;
  /** Where follow() heads: the map's bounds from above its look direction;
   *  nothing while the scene is empty. */
  std::optional<TOrbit> orbitTarget() const;
  /** One step from orbitSet towards `target`, applied to the camera. */
  void glideTo(const TOrbit& target);
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
}  // namespace roislam::gui
