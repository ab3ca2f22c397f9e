/* feature-bench: compares SIFT, SURF (roislam's), ORB and AKAZE on real frames
 * warped by known homographies. Thin front end over CFeatureBench. */
#include <roislam/common/ProcessTuning.h>
#include <roislam/featurebench/CFeatureBench.h>

#include <CLI/CLI.hpp>
#include <iostream>
#include <opencv2/core/utility.hpp>

int main(int argc, char** argv)
{
  roislam::common::tuneAllocatorForImages();
  using roislam::featurebench::CFeatureBench;
  CLI::App app{
      "feature-bench: keypoints/frame, ms/frame, repeatability and matching score of "
      "SIFT, SURF, ORB and AKAZE under rotation, scale, blur and brightness changes"};
  CFeatureBench::TOptions o;
  std::string extractors = "sift,surf,orb,akaze";
  std::string transforms = "rot15,rot30,rot45,scale1.2,scale1.5,scale2.0,blur,brightness";
  bool json = false;
  int threads = -1;
  app.add_option("--input", o.input, "TUM sequence folder (rgb.txt, rgb/)")->required();
  app.add_option("--frames", o.frames, "frames used, evenly spaced")->capture_default_str();
  app.add_option("--max-features", o.max_features, "same cap for all extractors, 0 = none")
      ->capture_default_str();
  app.add_option("--extractors", extractors, "comma list: sift,surf,orb,akaze")
      ->capture_default_str();
  app.add_option("--transforms", transforms, "comma list of transformations")
      ->capture_default_str();
  app.add_option("--pixel-tolerance", o.pixel_tolerance, "correspondence distance, px")
      ->capture_default_str();
  app.add_option("--border-margin", o.border_margin, "common-part margin, px")
      ->capture_default_str();
  app.add_option("--threads", threads, "OpenCV threads (default: OpenCV's choice)");
  app.add_flag("--json", json, "print JSON instead of the table");
  CLI11_PARSE(app, argc, argv);
  try
  {
    o.extractors = CFeatureBench::parseList(extractors);
    o.transforms = CFeatureBench::parseList(transforms);
    if (threads >= 0)
      cv::setNumThreads(threads);
    const CFeatureBench bench(o);
    std::cerr << "feature-bench: running on " << o.input << " ..." << std::endl;
    const auto result = bench.run();
    std::cout << (json ? CFeatureBench::toJson(result) + "\n" : CFeatureBench::toTable(result));
    return 0;
  }
  catch (const std::exception& e)
  {
    std::cerr << "feature-bench: error: " << e.what() << std::endl;
    return 1;
  }
}
