/* roi-graphslam-engine: MRPT's CGraphSlamEngine<CNetworkOfPoses3DInf> on an
 * RGB-D rawlog, with graphslam-engine's command line and our deciders by
 * name (CKeyframeNRD, CKeyframeERD, CKeyframeGSO by default), headless
 * unless --gui (roi-graphslam's live view); writes roi-graphslam's outputs
 * into --output-dir. The work is in graphslam::CRoiGraphSlamEngineApp.
 */
#include <roislam/common/ProcessTuning.h>
#include <roislam/graphslam/CRoiGraphSlamEngineApp.h>
#include <roislam/graphslam/SlamMain.h>
#include <roislam/gui/CLiveViewSession.h>

#include <CLI/CLI.hpp>
#include <iostream>
#include <string>

namespace
{
using roislam::graphslam::CRoiGraphSlamEngineApp;

/** Command-line values that are not TArguments fields as they stand. */
struct TCliFlags
{
  std::string gt;
  bool listNode = false, listEdge = false, listRegs = false, listOpt = false, noSnapshot = false;
  bool allowPartial = false;
  bool listing() const { return listNode || listEdge || listRegs || listOpt; }
};

/** graphslam-engine's options, ours, and the live view's flags (in --help's order). */
void addOptions(
    CLI::App& cli, CRoiGraphSlamEngineApp::TArguments& args, TCliFlags& flags,
    roislam::gui::CLiveViewSession& liveView)
{
  cli.add_option("-i,--ini-file", args.iniFile, ".ini configuration (config/graphslam-engine.ini)");
  cli.add_option("-r,--rawlog", args.rawlog, "Rawlog of CObservation3DRangeScan (tum2rawlog)");
  cli.add_option("-g,--ground-truth", flags.gt, "Ground truth, TUM format (NAME.groundtruth.txt)");
  cli.add_option("-n,--node-reg", args.deciders.node, "Node registration decider")
      ->capture_default_str();
  cli.add_option("-e,--edge-reg", args.deciders.edge, "Edge registration decider")
      ->capture_default_str();
  cli.add_option("-o,--optimizer", args.deciders.optimizer, "GraphSlam optimizer")
      ->capture_default_str();
  cli.add_flag("--3d", args.threeD, "Construct a 3-D graph (CPose3DPDFGaussianInf): the default");
  cli.add_flag("--2d", args.twoD, "Construct a 2-D graph: not supported (RGB-D deciders)");
  cli.add_flag(
      "--disable-visuals", args.disableVisuals,
      "No MRPT engine window: always the case (the live view is --gui)");
  cli.add_flag("--list-node-regs", flags.listNode, "List the node registration deciders and exit");
  cli.add_flag("--list-edge-regs", flags.listEdge, "List the edge registration deciders and exit");
  cli.add_flag("--list-regs", flags.listRegs, "List all registration deciders and exit");
  cli.add_flag("--list-optimizers", flags.listOpt, "List the optimizers and exit");
  cli.add_option(
         "--camera", args.camera,
         "Sensor description: auto|fr1|fr2|fr3|icl|7scenes|ros|<file> (readout, depth noise)")
      ->capture_default_str();
  cli.add_option("--output-dir", args.outputDir, "Output folder")->capture_default_str();
  cli.add_flag("--no-snapshot", flags.noSnapshot, "Do not render snapshot.png");
  liveView.addFlags(cli);
  cli.add_flag("--overwrite", args.overwrite, "Replace an earlier output in --output-dir");
  cli.add_flag(
      "--allow-partial", flags.allowPartial,
      "Exit 0 when the evaluation or snapshot failed (else 3; summary.json says what)");
}

/** --list-*: prints the lists asked for; false when none was. */
bool listDeciders(const TCliFlags& flags)
{
  if (flags.listRegs || flags.listNode)
    std::cout << CRoiGraphSlamEngineApp::list("node");
  if (flags.listRegs || flags.listEdge)
    std::cout << CRoiGraphSlamEngineApp::list("edge");
  if (flags.listOpt)
    std::cout << CRoiGraphSlamEngineApp::list("optimizer");
  return flags.listing();
}
}  // namespace

int main(int argc, char** argv)
{
  roislam::common::tuneAllocatorForImages();
  CLI::App cli{
      "MRPT's graph-SLAM engine (3-D) with roislam's RGB-D deciders; graphslam-engine's options"};
  CRoiGraphSlamEngineApp::TArguments args;
  TCliFlags flags;
  roislam::gui::CLiveViewSession liveView("roi-graphslam-engine");
  addOptions(cli, args, flags, liveView);
  CLI11_PARSE(cli, argc, argv);

  if (listDeciders(flags))
    return 0;
  if (!flags.gt.empty())
    args.groundTruth = flags.gt;
  args.snapshot = !flags.noSnapshot;
  args.progress = [](const std::string& line) { std::cerr << line << std::endl; };
  const int rc = roislam::graphslam::slamMain(
      "roi-graphslam-engine", args.outputDir, flags.allowPartial,
      [&] { return liveView.runObserved<CRoiGraphSlamEngineApp>(args); });
  // A window that was open ends the process here, whatever happened.
  return liveView.end(rc);
}
