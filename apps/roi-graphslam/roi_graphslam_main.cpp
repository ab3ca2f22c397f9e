/* roi-graphslam: RGB-D graph SLAM (traditional, small-ROI or big-ROI front
 * end) on a TUM folder or rawlog; writes trajectory, graph, map, scene,
 * snapshot, frames.csv and summary.json into the output folder. All the work
 * is in roislam::graphslam::CRoiGraphSlamApp.
 */
#include <roislam/common/ExitStatus.h>
#include <roislam/common/ProcessTuning.h>
#include <roislam/graphslam/CRoiGraphSlamApp.h>

#include <CLI/CLI.hpp>
#include <iostream>
#include <string>

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
  CLI11_PARSE(cli, argc, argv);

  try
  {
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
    if (args.input.empty() || args.outputDir.empty())
      throw std::invalid_argument("--input and --output-dir are required");
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

    roislam::graphslam::CRoiGraphSlamApp app(args);
    const auto summary = app.run();
    std::cout << summary.resultLine() << std::endl;
    if (summary.failed)
    {
      std::cerr << "roi-graphslam: error: tracking failed: " << summary.lostFrames << " of "
                << summary.frames << " frames lost (outputs in " << args.outputDir << ")"
                << std::endl;
      return roislam::common::kExitError;
    }
    if (!summary.incomplete.empty())
    {
      std::cerr << "roi-graphslam: " << (allowPartial ? "warning" : "error")
                << ": incomplete outputs in " << args.outputDir << ": "
                << summary.incomplete.front()
                << (summary.incomplete.size() > 1 ? " (and more, see summary.json)" : "")
                << std::endl;
      return allowPartial ? roislam::common::kExitOk : roislam::common::kExitPartial;
    }
    return roislam::common::kExitOk;
  }
  catch (const std::exception& e)
  {
    // MRPT exceptions append a call stack after the first line.
    const std::string what = e.what();
    std::cerr << "roi-graphslam: error: " << what.substr(0, what.find('\n')) << std::endl;
    return 1;
  }
}
