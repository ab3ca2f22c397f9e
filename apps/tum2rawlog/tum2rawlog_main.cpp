/* tum2rawlog: converts a TUM RGB-D benchmark folder, an OpenNI .oni recording
 * or a live OpenNI2 device into an MRPT rawlog of CObservation3DRangeScan (see
 * roislam::io::CTum2RawlogApp for the format). */
#include <roislam/common/ProcessTuning.h>
#include <roislam/io/CTum2RawlogApp.h>

#include <CLI/CLI.hpp>
#include <iostream>

int main(int argc, char** argv)
{
  roislam::common::tuneAllocatorForImages();
  roislam::io::CTum2RawlogApp::TOptions opts;
  CLI::App cli{
      "Converts a TUM RGB-D folder, an .oni recording or an OpenNI2 device into an MRPT rawlog "
      "of CObservation3DRangeScan"};
  cli.add_option(
         "-i,--input", opts.input,
         "TUM sequence folder (rgb.txt, depth.txt, ...), .oni recording, openni2 (first "
         "device) or openni2://<uri>")
      ->required();
  cli.add_option("-o,--output", opts.output, "Output .rawlog file")->required();
  cli.add_option(
      "-c,--camera", opts.camera,
      "Sensor description: auto | fr1 | fr2 | fr3 | icl | 7scenes | ros | sensor-description / "
      "TCamera ini | "
      "yaml");
  cli.add_option("--max-frames", opts.maxFrames, "Stop after N frames (0 = all; live: required)");
  cli.add_option(
         "--max-time-difference", opts.tum.maxTimeDifference,
         "Colour/depth association window in seconds")
      ->check(CLI::PositiveNumber);
  cli.add_option("--compress", opts.compressLevel, "gz level of the rawlog (0-9)")
      ->check(CLI::Range(0, 9));
  CLI11_PARSE(cli, argc, argv);

  try
  {
    roislam::io::CTum2RawlogApp app(opts);
    app.logRegisterCallback(
        [](std::string_view msg, mrpt::system::VerbosityLevel, std::string_view,
           mrpt::Clock::time_point)
        {
          std::cerr << "tum2rawlog: " << msg;
          if (msg.empty() || msg.back() != '\n')
            std::cerr << '\n';
        });
    const auto r = app.run();
    std::cerr << "tum2rawlog: " << r.frames << " observations, " << r.skipped
              << " colour frames skipped, " << r.seconds << " s -> " << r.rawlog << "\n";
    return 0;
  }
  catch (const std::exception& e)
  {
    std::cerr << "tum2rawlog: error: " << e.what() << "\n";
    return 1;
  }
}
