/* cv-odometry: OpenCV's cv::rgbd odometry (RgbdOdometry, ICPOdometry or
 * RgbdICPOdometry), frame to frame, on a TUM folder or rawlog; writes
 * trajectory.txt and summary.json (ATE / RPE with ground truth, ms per frame).
 * All the work is in roislam::reference::CCvOdometryApp.
 */
#include <roislam/reference/CCvOdometryApp.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>
#include <string>

int main(int argc, char** argv)
{
  using roislam::reference::CCvOdometryApp;
  CLI::App cli{
      "cv-odometry: OpenCV's cv::rgbd odometry frame to frame, the reference for roislam's "
      "front end"};
  CCvOdometryApp::TArguments args;
  cli.add_option("--input", args.input, "TUM RGB-D folder or .rawlog")->required();
  cli.add_option("--output-dir", args.outputDir, "Output folder")->required();
  cli.add_option("--method", args.method, "rgbd | icp | rgbdicp (overrides the ini)")
      ->check(CLI::IsMember({"rgbd", "icp", "rgbdicp"}));
  cli.add_option("--ini", args.iniFile, "Options: MRPT ini with a [CvOdometry] section");
  cli.add_option(
      "--camera", args.camera, "Camera: auto|fr1|fr2|fr3|icl|7scenes|ros|<calibration file>");
  cli.add_option("--max-frames", args.maxFrames, "Process at most N frames (0 = all)");
  CLI11_PARSE(cli, argc, argv);
  try
  {
    args.progress = [](const std::string& line) { std::cerr << line << std::endl; };
    const auto s = CCvOdometryApp(args).run();
    char line[256];
    std::snprintf(
        line, sizeof(line), "frames %zu (failed %zu), %.1f ms/frame, ATE %s m", s.frames,
        s.failedFrames, s.msPerFrame,
        s.ateRmse ? std::to_string(*s.ateRmse).c_str() : "n/a (no ground truth)");
    std::cout << line << std::endl;
    return 0;
  }
  catch (const std::exception& e)
  {
    const std::string what = e.what();
    std::cerr << "cv-odometry: error: " << what.substr(0, what.find('\n')) << std::endl;
    return 1;
  }
}
