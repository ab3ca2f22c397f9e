/* A SLAM app's live view from its command line to its exit: the --gui*
 * flags, the window opened once the app has checked its arguments (so a
 * bad ini fails before a window appears), the observer handed to the run,
 * the screenshot and the wait after the outputs are written, and the end
 * of the process (exitAfterLiveView) when a window was open. Shared by
 * roi-graphslam and roi-graphslam-engine, so that both keep thin mains.
 *
 * Built in every configuration: without MRPT's wxWidgets windows
 * (ROISLAM_HAVE_GUI off) it has no window to open, and open() with --gui
 * throws one line saying the app was built without GUI, before any output.
 */
#pragma once

#include <roislam/graphslam/CSlamObserver.h>
#include <roislam/graphslam/TSlamSummary.h>

#include <memory>
#include <string>

namespace CLI
{
class App;
}

namespace roislam::gui
{
class CLiveView;

class CLiveViewSession
{
 public:
  /** What the user asked for on the command line. */
  struct TRequest
  {
    bool gui = false;        //!< --gui
    bool paused = false;     //!< --gui-paused (implies --gui)
    bool keepOpen = false;   //!< --gui-keep-open (implies --gui)
    std::string screenshot;  //!< --gui-screenshot FILE (implies --gui)
    /** Any of the flags given: a window is wanted. */
    bool wanted() const { return gui || paused || keepOpen || !screenshot.empty(); }
  };

  /** `appName` names the window and prefixes warnings ("roi-graphslam"). */
  explicit CLiveViewSession(std::string appName);
  ~CLiveViewSession();
  CLiveViewSession(const CLiveViewSession&) = delete;
  CLiveViewSession& operator=(const CLiveViewSession&) = delete;

  /** Adds --gui, --gui-paused, --gui-screenshot and --gui-keep-open to
   *  `cli`; they fill the session's request. */
  void addFlags(CLI::App& cli);

  /** Opens the window when one is wanted, with [LiveView] of `iniFile`;
   *  's' saves screenshots into `outputDir`. Throws a one-line
   *  std::runtime_error "--gui: ..." when there is no display, the window
   *  cannot be made, or the build has no GUI; std::invalid_argument naming
   *  the file and key for a bad [LiveView]. Does nothing without --gui. */
  void open(const std::string& iniFile, const std::string& outputDir);

  /** The run's observer: the window, or null without one. */
  graphslam::CSlamObserver* observer() const;

  /** After the outputs are written: "finished" in the window, the asked
   *  screenshot (a failure only warns: the outputs are complete), then the
   *  wait for the user with --gui-keep-open. Does nothing without a window. */
  void finish(const std::string& outputDir);

  /** The run both apps hand to slamMain: the app built from `args` (it
   *  checks them before a window opens), the window opened, the run
   *  observed, then finish(). TApp: CRoiGraphSlamApp or
   *  CRoiGraphSlamEngineApp (TArguments with iniFile and outputDir). */
  template <class TApp>
  graphslam::TSlamSummary runObserved(const typename TApp::TArguments& args)
  {
    TApp app(args);
    open(args.iniFile, args.outputDir);
    app.setObserver(observer());
    const graphslam::TSlamSummary summary = app.run();
    finish(args.outputDir);
    return summary;
  }

  /** main()'s last call: returns `rc` when no window was opened; otherwise
   *  closes it and ends the process with `rc` (exitAfterLiveView, which says
   *  why MRPT's wx thread needs this). */
  int end(int rc);

 private:
  std::string m_appName;
  TRequest m_request;
  /** The window, owned as the run's observer (the type every build knows);
   *  m_window is the same object for the window's own calls. */
  std::unique_ptr<graphslam::CSlamObserver> m_view;
  CLiveView* m_window = nullptr;
};
}  // namespace roislam::gui
