#include <roislam/graphslam/SlamMain.h>

#include <exception>
#include <iostream>

namespace roislam::graphslam
{
int slamMain(
    const std::string& app, const std::string& outputDir, const std::function<TSlamSummary()>& run)
{
  try
  {
    const TSlamSummary summary = run();
    std::cout << summary.resultLine() << std::endl;
    if (!summary.failed)
      return 0;
    std::cerr << app << ": error: tracking failed: " << summary.lostFrames << " of "
              << summary.frames << " frames lost (outputs in " << outputDir << ")" << std::endl;
    return 1;
  }
  catch (const std::exception& e)
  {
    // MRPT exceptions append a call stack after the first line.
    const std::string what = e.what();
    std::cerr << app << ": error: " << what.substr(0, what.find('\n')) << std::endl;
    return 1;
  }
}
}  // namespace roislam::graphslam
