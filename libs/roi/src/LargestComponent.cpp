#include "roislam/roi/LargestComponent.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace roislam::roi
{
namespace
{
struct TRun
{
  int y, x0, x1;  // inclusive
};

int findRoot(std::vector<int>& parent, int i)
{
  int r = i;
  while (parent[static_cast<std::size_t>(r)] != r)
    r = parent[static_cast<std::size_t>(r)];
  while (parent[static_cast<std::size_t>(i)] != r)
  {
    const int next = parent[static_cast<std::size_t>(i)];
    parent[static_cast<std::size_t>(i)] = r;
    i = next;
  }
  return r;
}

/** First index >= x in [x, end) whose byte is (zero == wantZero), or end. */
int scan(const std::uint8_t* row, int x, int end, bool wantZero)
{
  // Skip whole 8-byte words of the other kind first (masks are mostly long
  // stretches of 0 or 255).
  while (x + 8 <= end)
  {
    std::uint64_t w;
    std::memcpy(&w, row + x, 8);
    if (wantZero ? w == ~std::uint64_t{0} : w == 0)
      x += 8;
    else
      break;
  }
  while (x < end && ((row[x] == 0) != wantZero))
    ++x;
  return x;
}
}  // namespace

std::optional<TComponent> largestComponent(const cv::Mat& mask)
{
  if (mask.type() != CV_8UC1)
    throw std::invalid_argument("largestComponent: expected a CV_8UC1 mask");
  std::vector<TRun> runs;
  std::vector<int> parent;
  int prevBegin = 0, prevEnd = 0;  // runs of the previous row
  for (int y = 0; y < mask.rows; ++y)
  {
    const auto* row = mask.ptr<std::uint8_t>(y);
    const int begin = static_cast<int>(runs.size());
    int x = 0;
    while (x < mask.cols)
    {
      // Fully-set words only skip 0xFF bytes; other non-zero values take the
      // byte loop, which is still correct.
      x = scan(row, x, mask.cols, false);
      if (x >= mask.cols)
        break;
      const int x0 = x;
      x = scan(row, x, mask.cols, true);
      runs.push_back({y, x0, x - 1});
      parent.push_back(static_cast<int>(parent.size()));
    }
    const int end = static_cast<int>(runs.size());
    // 8-connectivity: runs of adjacent rows touch when they overlap after
    // widening by one pixel. Both lists are sorted by x: one sweep.
    int p = prevBegin;
    for (int c = begin; c < end; ++c)
    {
      const auto& cur = runs[static_cast<std::size_t>(c)];
      while (p < prevEnd && runs[static_cast<std::size_t>(p)].x1 < cur.x0 - 1)
        ++p;
      for (int q = p; q < prevEnd && runs[static_cast<std::size_t>(q)].x0 <= cur.x1 + 1; ++q)
      {
        // Union; the earlier run (raster order) stays the root, so each
        // root is its component's first run.
        const int a = findRoot(parent, c), b = findRoot(parent, q);
        if (a != b)
          parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
      }
    }
    prevBegin = begin;
    prevEnd = end;
  }
  if (runs.empty())
    return std::nullopt;

  struct TAcc
  {
    int area = 0, x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  };
  std::vector<TAcc> acc(runs.size());
  for (std::size_t i = 0; i < runs.size(); ++i)
  {
    const auto& r = runs[i];
    auto& a = acc[static_cast<std::size_t>(findRoot(parent, static_cast<int>(i)))];
    if (a.area == 0)
    {
      a.x0 = r.x0;
      a.x1 = r.x1;
      a.y0 = a.y1 = r.y;
    }
    a.area += r.x1 - r.x0 + 1;
    a.x0 = std::min(a.x0, r.x0);
    a.x1 = std::max(a.x1, r.x1);
    a.y1 = std::max(a.y1, r.y);
  }
  std::size_t best = 0;
  for (std::size_t i = 1; i < acc.size(); ++i)
    if (acc[i].area > acc[best].area)
      best = i;  // strict: on ties the earlier root (first in raster order) stays
  const auto& a = acc[best];
  TComponent out;
  out.box = cv::Rect(a.x0, a.y0, a.x1 - a.x0 + 1, a.y1 - a.y0 + 1);
  out.area = a.area;
  return out;
}
}  // namespace roislam::roi
