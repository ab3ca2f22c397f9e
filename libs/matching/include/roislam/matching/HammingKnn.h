/* Exact brute-force k-nearest-neighbour search of binary descriptors under
 * the Hamming distance: the result of cv::BFMatcher(cv::NORM_HAMMING).knnMatch
 * (same matches, distances and order: ascending distance, the lower train
 * index first among equal ones), at a fraction of its cost.
 *
 * Why not OpenCV's: its brute force calls cv::hal::normHamming once per
 * descriptor pair, and each call opens a trace region (OpenCV's
 * instrumentation, there even when tracing is off). On fr1/rpy with ORB that
 * call overhead was most of the matching time, and matching about half of the
 * traditional front end's (perf, stop 32). Here a pair costs four 64-bit
 * popcounts for ORB's 32 bytes.
 */
#pragma once

#include <opencv2/core/mat.hpp>
#include <opencv2/core/types.hpp>
#include <vector>

namespace roislam::matching
{
/** For each row of query, its k nearest rows of train (k >= 1; fewer when
 *  train has fewer rows). Both CV_8U with the same number of columns, or
 *  either empty (then one empty list per query row). Throws
 *  std::invalid_argument otherwise. */
std::vector<std::vector<cv::DMatch>> hammingKnn(const cv::Mat& query, const cv::Mat& train, int k);
}  // namespace roislam::matching
