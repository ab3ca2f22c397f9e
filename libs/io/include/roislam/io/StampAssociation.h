/* Timestamp association with the semantics of the TUM benchmark's
 * associate.py: every pair (a, b) with |a - (b + offset)| < maxDifference is a
 * candidate; candidates are taken greedily by smallest difference, each stamp
 * used at most once. Used for colour/depth pairing and ground-truth matching.
 */
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

namespace roislam::io
{
/** Returns index pairs (i into a, j into b), sorted by i. Inputs need not be
 *  sorted. Ties are broken by (i, j) so the result is deterministic. */
std::vector<std::pair<std::size_t, std::size_t>> associateStamps(
    const std::vector<double>& a, const std::vector<double>& b, double maxDifference,
    double offset = 0);
}  // namespace roislam::io
