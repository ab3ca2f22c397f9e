/* The reference section of report.md: per sequence each of OpenCV's
 * cv::rgbd odometries (test 0, cv-odometry), then our best and worst
 * trajectory of Tests 2-4 on it. Called by CReportWriter::render; private
 * to libs/bench.
 */
#pragma once

#include <roislam/bench/TRunRecord.h>

#include <ostream>
#include <vector>

namespace roislam::bench::report
{
/** `ref`: the test-0 records (not empty); `all`: every record, in plan order. */
void renderReference(
    std::ostream& md, const std::vector<const TRunRecord*>& ref,
    const std::vector<const TRunRecord*>& all);
}  // namespace roislam::bench::report
