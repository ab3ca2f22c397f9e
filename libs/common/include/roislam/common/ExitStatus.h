/* The exit status of every roislam app (README "Exit status"), so scripts and
 * roi-bench can tell a complete run from a partial one.
 */
#pragma once

namespace roislam::common
{
/** Everything asked for was written. */
constexpr int kExitOk = 0;
/** Nothing new was written (bad input or configuration, unwritable output,
 *  any error), or the run itself failed (roi-graphslam: frames lost with
 *  strict_roi; its outputs are written and summary.json says "failed"). */
constexpr int kExitError = 1;
/** The outputs are written but part of them failed (roi-graphslam: the
 *  evaluation against ground truth or the snapshot); summary.json says
 *  "partial": true and names the failure. --allow-partial returns 0 instead. */
constexpr int kExitPartial = 3;
}  // namespace roislam::common
