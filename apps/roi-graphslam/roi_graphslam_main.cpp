/* roi-graphslam: RGB-D graph SLAM (traditional, small-ROI or big-ROI front
 * end) on a TUM folder or rawlog; writes trajectory, graph, map, scene,
 * snapshot, frames.csv and summary.json into the output folder. All the work
 * is in roislam::graphslam::CRoiGraphSlamApp.
 */
#include <roislam/common/ProcessTuning.h>
#include <roislam/graphslam/CRoiGraphSlamApp.h>
#include <roislam/graphslam/SlamMain.h>
#include <roislam/gui/CLiveViewSession.h>

#include <CLI/CLI.hpp>
#include <iostream>
#include <stdexcept>
#include <string>

namespace
{
using roislam::graphslam::CRoiGraphSlamApp;

/** Command-line values that are not TArguments fields as they stand: unset
 *  ones leave the ini's setting alone. */
struct TCliFlags
{
  std::string mode, feature;
  int maxFeatures = -1;
  bool noSnapshot = false, listNode = false, listEdge = false, strict = false;
  bool allowPartial = false;
};

void addOptions(CLI::App& cli, CRoiGraphSlamApp::TArguments& args, TCliFlags& flags)
{
  cli.add_option("--ini", args.iniFile, "Configuration (MRPT ini), e.g. config/traditional.ini");
  cli.add_option("--input", args.input, "TUM RGB-D folder or .rawlog");
  cli.add_option("--output-dir", args.outputDir, "Output folder");
  cli.add_option("--mode", flags.mode, "Front end (overrides the ini)")
      ->check(CLI::IsMember({"traditional", "roi_small", "roi_big"}, CLI::ignore_case));
  cli.add_option("--feature", flags.feature, "Feature type (overrides the ini)")
      ->check(CLI::IsMember({"sift", "surf", "orb"}, CLI::ignore_case));
  cli.add_option("--max-features", flags.maxFeatures, "Cap on features per frame, 0 = none")
      ->check(CLI::NonNegativeNumber);
  cli.add_flag(
      "--strict-roi", flags.strict, "ROI modes: no fallback (the dissertation's behaviour)");
  cli.add_option(
      "--camera", args.camera, "Camera: auto|fr1|fr2|fr3|icl|7scenes|ros|<calibration file>");
  cli.add_option("--max-frames", args.maxFrames, "Process at most N frames (0 = all)");
  cli.add_flag("--no-snapshot", flags.noSnapshot, "Do not render snapshot.png");
  cli.add_flag("--overwrite", args.overwrite, "Replace an earlier output in --output-dir");
  cli.add_flag(
      "--allow-partial", flags.allowPartial,
      "Exit 0 when the evaluation or snapshot failed (else 3; summary.json says what)");
  cli.add_flag("--list-node-regs", flags.listNode, "List the node registration deciders and exit");
  cli.add_flag("--list-edge-regs", flags.listEdge, "List the edge registration deciders and exit");
}

void applyFlags(const TCliFlags& flags, CRoiGraphSlamApp::TArguments& args)
{
  if (!flags.mode.empty())
    args.mode = flags.mode;
  if (!flags.feature.empty())
    args.feature = flags.feature;
  if (flags.maxFeatures >= 0)
    args.maxFeatures = flags.maxFeatures;
  if (flags.strict)
    args.strictRoi = true;
  args.snapshot = !flags.noSnapshot;
  args.progress = [](const std::string& line) { std::cerr << line << std::endl; };
}
}  // namespace

int main(int argc, char** argv)
{
  roislam::common::tuneAllocatorForImages();
  CLI::App cli{"RGB-D graph SLAM with ROI landmark tracking (MRPT 3-D pose graph)"};
  CRoiGraphSlamApp::TArguments args;
  TCliFlags flags;
  addOptions(cli, args, flags);
  roislam::gui::CLiveViewSession liveView("roi-graphslam");
  liveView.addFlags(cli);
  CLI11_PARSE(cli, argc, argv);

  if (flags.listNode)
    std::cout << "Node registration deciders (3-D):\n" << CRoiGraphSlamApp::listRegistrars("node");
  if (flags.listEdge)
    std::cout << "Edge registration deciders (3-D):\n" << CRoiGraphSlamApp::listRegistrars("edge");
  if (flags.listNode || flags.listEdge)
    return 0;
  applyFlags(flags, args);
  const int rc = roislam::graphslam::slamMain(
      "roi-graphslam", args.outputDir, flags.allowPartial,
      [&]
      {
        if (args.input.empty() || args.outputDir.empty())
          throw std::invalid_argument("--input and --output-dir are required");
        return liveView.runObserved<CRoiGraphSlamApp>(args);
      });
  // A window that was open ends the process here, whatever happened.
  return liveView.end(rc);
}
