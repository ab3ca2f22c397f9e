/* roi-landmarks: runs the ROI landmark pipeline (the dissertation's Test 1) on
 * an RGB-D sequence and writes frames.csv, landmarks/, landmarks.db and
 * summary.json into the output folder; with --kf-slam also MRPT's EKF-SLAM
 * on the landmarks. All the work is in
 * roislam::landmarks::CRoiLandmarksApp.
 */
#include <roislam/common/ProcessTuning.h>
#include <roislam/landmarks/CRoiLandmarksApp.h>

#include <CLI/CLI.hpp>
#include <iostream>
#include <string>

int main(int argc, char** argv)
{
  roislam::common::tuneAllocatorForImages();
  CLI::App cli{"ROI landmark database on an RGB-D sequence (Test 1: the pipeline alone)"};
  roislam::landmarks::CRoiLandmarksApp::TArguments args;
  std::string feature, roi, rawlog;
  int maxFeatures = -1;
  cli.add_option("--ini", args.iniFile, "Configuration (MRPT ini), e.g. config/roi_landmarks.ini");
  cli.add_option("--input", args.input, "TUM RGB-D folder or .rawlog")->required();
  cli.add_option("--output-dir", args.outputDir, "Output folder")->required();
  cli.add_option("--feature", feature, "Feature type (overrides the ini)")
      ->check(CLI::IsMember({"sift", "surf", "orb"}, CLI::ignore_case));
  cli.add_option("--max-features", maxFeatures, "Cap on features per frame, 0 = none")
      ->check(CLI::NonNegativeNumber);
  cli.add_option("--roi", roi, "ROI preset (overrides the ini)")
      ->check(CLI::IsMember({"small", "big"}, CLI::ignore_case));
  cli.add_option(
      "--output-rawlog", rawlog, "Also write an annotated rawlog (3-D scans + landmarks)");
  cli.add_option(
      "--camera", args.camera, "Camera: auto|fr1|fr2|fr3|icl|7scenes|ros|<calibration file>");
  cli.add_option("--max-frames", args.maxFrames, "Process at most N frames (0 = all)");
  cli.add_flag("--overwrite", args.overwrite, "Replace an earlier output in --output-dir");
  cli.add_flag(
      "--kf-slam", args.kfSlam,
      "Also write kf-slam.rawlog (odometry + landmarks) and run MRPT's EKF-SLAM on it "
      "([KfSlam] options): kf-slam/trajectory.txt");
  CLI11_PARSE(cli, argc, argv);

  if (!feature.empty())
    args.feature = feature;
  if (!roi.empty())
    args.roiPreset = roi;
  if (maxFeatures >= 0)
    args.maxFeatures = maxFeatures;
  if (!rawlog.empty())
    args.outputRawlog = rawlog;
  args.progress = [](const std::string& line) { std::cerr << line << std::endl; };
  try
  {
    roislam::landmarks::CRoiLandmarksApp app(args);
    app.run();
    return 0;
  }
  catch (const std::exception& e)
  {
    // MRPT exceptions append a call stack after the first line.
    const std::string what = e.what();
    std::cerr << "roi-landmarks: error: " << what.substr(0, what.find('\n')) << std::endl;
    return 1;
  }
}
