/* The live view of a SLAM run (roi-graphslam --gui): one MRPT window
 * (mrpt::gui::CDisplayWindow3D, wxWidgets) with the growing map,
 * trajectory, keyframes, loop closures and ground truth on the left
 * (CLiveScene; the mouse turns and zooms it, 'f' goes back to following the
 * map), the current colour image with ROI, region, features and tracking
 * method top right and the depth image below it (drawFrameOverlay), and a
 * status line (frame, fps, keyframes, closures, fallbacks).
 *
 * Never in the way: as a CSlamObserver it only copies a few numbers per
 * frame on the SLAM thread (the images at most refresh_hz times a second,
 * the keyframe clouds decimated) into a queue; its own thread draws them
 * at most refresh_hz times a second, and MRPT's wx thread renders. Keys
 * (handled on MRPT's wx thread): space pauses / resumes the run (the SLAM
 * thread waits in onFrame()), 's' saves a screenshot into the session's
 * folder, 'q' stops the run (stopRequested(): the app still writes every
 * output), closing the window does the same as 'q'.
 *
 * ini section [LiveView] (TOptions), units in brackets:
 *  - refresh_hz               [1/s] in [0.5, 60] (2): redraws per second at
 *                             most; each redraw also costs MRPT's renderer
 *                             (Mesa's software GL under Xvfb: the SLAM run
 *                             shares the CPU with it)
 *  - max_cpu_share            (0, 1] (0.03): the view redraws less often
 *                             (down to every 3 s) while its threads use more
 *                             CPU than this share of the SLAM threads'
 *                             (CRedrawBudget), so that it costs the run at
 *                             most about this much on a busy machine
 *  - width, height            [px] >= 320 / 240 (1024, 576): window size
 *  - map_points_per_keyframe  int >= 1 (1000): points of each keyframe's
 *                             map cloud ([GraphSlam] map_decimation) drawn
 *  - point_size_px            [px] > 0 (2)
 *  - flash_s                  [s] >= 0 (2): a new loop closure flashes
 *  - max_depth_m              [m] > 0 (5): depth image colour scale
 *  - follow                   bool (true): the view follows the map until
 *                             the mouse moves it
 * A bad value throws std::invalid_argument "[LiveView] key: why".
 *
 * Used by apps/roi-graphslam (--gui); needs an X display (GDK_BACKEND is
 * set to x11 unless the user chose one).
 */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <roislam/graphslam/CSlamObserver.h>

#include <functional>
#include <memory>
#include <string>

namespace roislam::gui
{
class CLiveView : public graphslam::CSlamObserver
{
 public:
  struct TOptions : public mrpt::config::CLoadableOptions
  {
    double refresh_hz = 2;
    double max_cpu_share = 0.03;
    int width = 1024;
    int height = 576;
    int map_points_per_keyframe = 1000;
    double point_size_px = 2;
    double flash_s = 2;
    double max_depth_m = 5;
    bool follow = true;

    void loadFromConfigFile(
        const mrpt::config::CConfigFileBase& source, const std::string& section) override;
    void saveToConfigFile(
        mrpt::config::CConfigFileBase& target, const std::string& section) const override;
    /** Throws std::invalid_argument "[LiveView] key: why". */
    void validate() const;
  };

  /** What the app sets (not from the ini). */
  struct TSession
  {
    /** Window title prefix and log lines' prefix. */
    std::string appName = "roi-graphslam";
    /** 's' saves screenshot-<frame>.png here (created if needed). */
    std::string screenshotDir = ".";
    /** Start paused (space starts the run). */
    bool startPaused = false;
    /** One line per event worth telling (screenshot saved, paused...); may be empty. */
    std::function<void(const std::string&)> log;
  };

  /** [LiveView] of `iniFile` (empty: defaults), unknown keys refused:
   *  throws naming the file and key. */
  static TOptions loadOptions(const std::string& iniFile);

  /** Opens the window. Throws std::runtime_error with one line when there is
   *  no display or the window cannot be created. */
  CLiveView(const TOptions& options, TSession session);
  /** Stops drawing and closes the window. */
  ~CLiveView() override;
  CLiveView(const CLiveView&) = delete;
  CLiveView& operator=(const CLiveView&) = delete;

  void onStart(const io::CFrameSource& source, const graphslam::CSlamContext& context) override;
  /** Key-press screenshots go to `dir` from now on (TSession::screenshotDir). */
  void onOutputFolder(const std::string& dir) override;
  void onFrame(
      const frontend::TFrameResult& result, const io::TRGBDFrame& frame,
      const graphslam::CSlamContext& context) override;
  void onOptimized(const graphslam::TGraph& graph, const graphslam::CSlamContext& context) override;
  /** 'q' was pressed or the window closed. */
  bool stopRequested() const override;

  /** Draws everything received so far, then saves the window as a PNG
   *  (through a temporary file). Throws std::runtime_error naming the file
   *  (or saying the window is closed) on failure. */
  void saveScreenshot(const std::string& pngFile);
  /** A line shown under the status line (e.g. "finished"). */
  void setMessage(const std::string& text);
  /** Blocks until 'q' is pressed or the window is closed. */
  void waitUntilClosed();
  bool paused() const;

 private:
  struct TImpl;
  std::unique_ptr<TImpl> m_impl;
};

/** Ends the process once a live view was open (and is destroyed), skipping
 *  static destructors: MRPT 2.5 stops its wx thread at exit by sleeping
 *  100 ms (WxSubsystem::waitWxShutdownsIfNoWindows) and then destroys
 *  statics while GTK may still run on that thread: 3 of 18 parallel runs
 *  under Xvfb aborted there ("free(): invalid pointer"). The C and C++
 *  streams are flushed first; every output file is complete before (they
 *  are written through renames). */
[[noreturn]] void exitAfterLiveView(int code);
}  // namespace roislam::gui
