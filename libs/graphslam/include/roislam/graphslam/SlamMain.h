/* The end of roi-graphslam's and roi-graphslam-engine's main(): the same
 * console contract for both (the run's result line on stdout; a one-line
 * "<app>: error: ..." on stderr and exit code 1 for an error or a run whose
 * tracking failed; exit code 3 for outputs written but partial, see
 * common/ExitStatus.h).
 */
#pragma once

#include <roislam/graphslam/TSlamSummary.h>

#include <functional>
#include <string>

namespace roislam::graphslam
{
/** Calls `run` (which builds the app and runs it) and returns main()'s exit
 *  code: 0 after printing TSlamSummary::resultLine(); 1 after "<app>: error:
 *  tracking failed: ..." (the outputs in `outputDir` are written) or the
 *  first line of an exception's message (MRPT's append a call stack);
 *  common::kExitPartial (3) after "<app>: error: incomplete outputs in ...:
 *  <first TSlamSummary::incomplete>" unless `allowPartial` (then a warning
 *  and 0). */
int slamMain(
    const std::string& app, const std::string& outputDir, bool allowPartial,
    const std::function<TSlamSummary()>& run);
}  // namespace roislam::graphslam
