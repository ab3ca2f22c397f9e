/* roi-graphslam: RGB-D graph SLAM (traditional, small-ROI or big-ROI front
 * end) on a TUM folder or rawlog; writes trajectory, graph, map, scene,
 * snapshot, frames.csv and summary.json into the output folder. All the work
 * is in roislam::graphslam::CRoiGraphSlamApp.
 */
#include <roislam/common/ProcessTuning.h>
#include <roislam/graphslam/CRoiGraphSlamApp.h>
#include <roislam/graphslam/SlamMain.h>

#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#if ROISLAM_HAVE_GUI
#include <roislam/gui/CLiveView.h>
#endif

namespace
{
/** The --gui* flags. */
struct TGuiArgs
{
  bool enabled = false, paused = false, keepOpen = false;
  std::string screenshot;
};

#if ROISLAM_HAVE_GUI
std::unique_ptr<roislam::gui::CLiveView> openLiveView(
    const TGuiArgs& g, const roislam::graphslam::CRoiGraphSlamApp::TArguments& args)
{
  if (!g.enabled)
    return nullptr;
  roislam::gui::CLiveView::TSession session;
  session.screenshotDir = args.outputDir;
  session.startPaused = g.paused;
  session.log = [](const std::string& line) { std::cerr << line << std::endl; };
  return std::make_unique<roislam::gui::CLiveView>(
      roislam::gui::CLiveView::loadOptions(args.iniFile), session);
}

/** Closes the window and ends the process (exitAfterLiveView) when one was open. */
int endLiveView(std::unique_ptr<roislam::gui::CLiveView> view, int rc)
{
  if (!view)
    return rc;
  view.reset();
  roislam::gui::exitAfterLiveView(rc);
}

/** After the outputs are written: the asked screenshot, then wait for the
 *  user when asked to. A window closed meanwhile only warns: the run's
 *  outputs are complete. */
void finishLiveView(roislam::gui::CLiveView* view, const TGuiArgs& g, const std::string& outDir)
{
  if (!view)
    return;
  view->setMessage(
      "finished: outputs in " + outDir + (g.keepOpen ? "   (q or closing the window ends)" : ""));
  if (!g.screenshot.empty())
  {
    try
    {
      view->saveScreenshot(g.screenshot);
    }
    catch (const std::exception& e)
    {
      std::cerr << "roi-graphslam: warning: " << e.what() << std::endl;
    }
  }
  if (g.keepOpen)
    view->waitUntilClosed();
}
#else
// Built without the live view: --gui fails with one line, before any output.
using TNoView = roislam::graphslam::CSlamObserver;
std::unique_ptr<TNoView> openLiveView(
    const TGuiArgs& g, const roislam::graphslam::CRoiGraphSlamApp::TArguments&)
{
  if (g.enabled)
    throw std::runtime_error(
        "--gui: roi-graphslam was built without GUI (MRPT's wxWidgets windows were not found)");
  return nullptr;
}
void finishLiveView(TNoView*, const TGuiArgs&, const std::string&) {}
int endLiveView(std::unique_ptr<TNoView>, int rc)
{
  return rc;
}
#endif
}  // namespace

int main(int argc, char** argv)
{
  roislam::common::tuneAllocatorForImages();
  CLI::App cli{"RGB-D graph SLAM with ROI landmark tracking (MRPT 3-D pose graph)"};
  roislam::graphslam::CRoiGraphSlamApp::TArguments args;
  std::string mode, feature;
  int maxFeatures = -1;
  bool noSnapshot = false, listNode = false, listEdge = false, strict = false;
  bool allowPartial = false;
  cli.add_option("--ini", args.iniFile, "Configuration (MRPT ini), e.g. config/traditional.ini");
  cli.add_option("--input", args.input, "TUM RGB-D folder or .rawlog");
  cli.add_option("--output-dir", args.outputDir, "Output folder");
  cli.add_option("--mode", mode, "Front end (overrides the ini)")
      ->check(CLI::IsMember({"traditional", "roi_small", "roi_big"}, CLI::ignore_case));
  cli.add_option("--feature", feature, "Feature type (overrides the ini)")
      ->check(CLI::IsMember({"sift", "surf", "orb"}, CLI::ignore_case));
  cli.add_option("--max-features", maxFeatures, "Cap on features per frame, 0 = none")
      ->check(CLI::NonNegativeNumber);
  cli.add_flag("--strict-roi", strict, "ROI modes: no fallback (the dissertation's behaviour)");
  cli.add_option("--camera", args.camera, "Camera: auto|fr1|fr2|fr3|ros|<calibration file>");
  cli.add_option("--max-frames", args.maxFrames, "Process at most N frames (0 = all)");
  cli.add_flag("--no-snapshot", noSnapshot, "Do not render snapshot.png");
  cli.add_flag("--overwrite", args.overwrite, "Replace an earlier output in --output-dir");
  cli.add_flag(
      "--allow-partial", allowPartial,
      "Exit 0 when the evaluation or snapshot failed (else 3; summary.json says what)");
  cli.add_flag("--list-node-regs", listNode, "List the node registration deciders and exit");
  cli.add_flag("--list-edge-regs", listEdge, "List the edge registration deciders and exit");
  TGuiArgs gui;
  cli.add_flag("--gui", gui.enabled, "Live view while SLAM runs (needs an X display)");
  cli.add_flag("--gui-paused", gui.paused, "--gui, starting paused (space starts the run)");
  cli.add_option("--gui-screenshot", gui.screenshot, "--gui: save the window as PNG at the end");
  cli.add_flag("--gui-keep-open", gui.keepOpen, "--gui: keep the window open after the run");
  CLI11_PARSE(cli, argc, argv);
  gui.enabled = gui.enabled || gui.paused || !gui.screenshot.empty() || gui.keepOpen;

  if (listNode || listEdge)
  {
    using roislam::graphslam::CRoiGraphSlamApp;
    if (listNode)
      std::cout << "Node registration deciders (3-D):\n"
                << CRoiGraphSlamApp::listRegistrars("node");
    if (listEdge)
      std::cout << "Edge registration deciders (3-D):\n"
                << CRoiGraphSlamApp::listRegistrars("edge");
    return 0;
  }
  if (!mode.empty())
    args.mode = mode;
  if (!feature.empty())
    args.feature = feature;
  if (maxFeatures >= 0)
    args.maxFeatures = maxFeatures;
  if (strict)
    args.strictRoi = true;
  args.snapshot = !noSnapshot;
  args.progress = [](const std::string& line) { std::cerr << line << std::endl; };
  // The live view outlives the run: a window that was open ends the process
  // through exitAfterLiveView() whatever happened (see there).
  decltype(openLiveView(gui, args)) view;
  const int rc = roislam::graphslam::slamMain(
      "roi-graphslam", args.outputDir, allowPartial,
      [&]
      {
        if (args.input.empty() || args.outputDir.empty())
          throw std::invalid_argument("--input and --output-dir are required");
        roislam::graphslam::CRoiGraphSlamApp app(args);  // checks the ini before a window opens
        view = openLiveView(gui, args);
        app.setObserver(view.get());
        const auto summary = app.run();
        finishLiveView(view.get(), gui, args.outputDir);
        return summary;
      });
  return endLiveView(std::move(view), rc);
}
