#include "roislam/io/StampAssociation.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace roislam::io
{
std::vector<std::pair<std::size_t, std::size_t>> associateStamps(
    const std::vector<double>& a, const std::vector<double>& b, double maxDifference, double offset)
{
  // Candidate generation over b sorted by time keeps this O((n + m) log m + k)
  // instead of associate.py's O(n m), with the same result.
  std::vector<std::size_t> bOrder(b.size());
  for (std::size_t j = 0; j < b.size(); ++j)
    bOrder[j] = j;
  std::sort(bOrder.begin(), bOrder.end(), [&](auto x, auto y) { return b[x] < b[y]; });
  std::vector<double> bSorted(b.size());
  for (std::size_t k = 0; k < b.size(); ++k)
    bSorted[k] = b[bOrder[k]] + offset;

  // The search window is padded because a[i] +- maxDifference is rounded: a
  // pair whose exact difference is just inside the window may sit on the
  // rounded bound. The exact |a - b| < maxDifference test below decides.
  const double pad = 1e-6 * std::max(1.0, maxDifference);
  std::vector<std::tuple<double, std::size_t, std::size_t>> candidates;
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    auto it = std::lower_bound(bSorted.begin(), bSorted.end(), a[i] - maxDifference - pad);
    for (; it != bSorted.end() && *it <= a[i] + maxDifference + pad; ++it)
    {
      const double d = std::abs(a[i] - *it);
      if (d < maxDifference)
        candidates.emplace_back(d, i, bOrder[static_cast<std::size_t>(it - bSorted.begin())]);
    }
  }
  std::sort(candidates.begin(), candidates.end());

  std::vector<bool> usedA(a.size(), false), usedB(b.size(), false);
  std::vector<std::pair<std::size_t, std::size_t>> matches;
  for (const auto& [d, i, j] : candidates)
  {
    if (usedA[i] || usedB[j])
      continue;
    usedA[i] = usedB[j] = true;
    matches.emplace_back(i, j);
  }
  std::sort(matches.begin(), matches.end());
  return matches;
}
}  // namespace roislam::io
