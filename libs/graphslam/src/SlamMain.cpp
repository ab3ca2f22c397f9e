#include <roislam/common/ExitStatus.h>
#include <roislam/graphslam/SlamMain.h>

#include <exception>
#include <iostream>

namespace roislam::graphslam
{
int slamMain(
    const std::string& app, const std::string& outputDir, bool allowPartial,
    const std::function<TSlamSummary()>& run)
{
  try
  {
    const TSlamSummary summary = run();
    std::cout << summary.resultLine() << std::endl;
    if (summary.failed)
    {
      std::cerr << app << ": error: tracking failed: " << summary.lostFrames << " of "
                << summary.frames << " frames lost (outputs in " << outputDir << ")" << std::endl;
      return common::kExitError;
    }
    if (summary.incomplete.empty())
      return common::kExitOk;
    std::cerr << app << ": " << (allowPartial ? "warning" : "error") << ": incomplete outputs in "
              << outputDir << ": " << summary.incomplete.front()
              << (summary.incomplete.size() > 1 ? " (and more, see summary.json)" : "")
              << std::endl;
    return allowPartial ? common::kExitOk : common::kExitPartial;
  }
  catch (const std::exception& e)
  {
    // MRPT exceptions append a call stack after the first line.
    const std::string what = e.what();
    std::cerr << app << ": error: " << what.substr(0, what.find('\n')) << std::endl;
    return common::kExitError;
  }
}
}  // namespace roislam::graphslam
