#include "roislam/matching/HammingKnn.h"

#include <algorithm>
#include <climits>
#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace roislam::matching
{
namespace
{
// x86-64's baseline has no POPCNT instruction: without it __builtin_popcountll
// is a table routine several times slower. The clone with it is chosen at
// load time on CPUs that have it (every x86-64 CPU since 2008); other
// architectures (ARM's CNT) need no clone.
#if defined(__x86_64__) && defined(__GNUC__)
#define ROISLAM_POPCNT_CLONES __attribute__((target_clones("popcnt", "default")))
#else
#define ROISLAM_POPCNT_CLONES
#endif

/** The k best (distance, index) of one query row over all train rows, in
 *  best[0..k), sorted; unused slots keep INT_MAX and index -1. */
ROISLAM_POPCNT_CLONES
void searchRow(
    const std::uint8_t* q, const cv::Mat& train, int words, int tailBytes, int k, int* bestDist,
    int* bestIdx)
{
  std::uint64_t qw[64];
  std::memcpy(qw, q, static_cast<std::size_t>(words) * 8);
  const std::uint8_t* qTail = q + words * 8;
  for (int j = 0; j < train.rows; ++j)
  {
    const std::uint8_t* t = train.ptr<std::uint8_t>(j);
    int d = 0;
    for (int w = 0; w < words; ++w)
    {
      std::uint64_t tw;
      std::memcpy(&tw, t + w * 8, 8);
      d += __builtin_popcountll(qw[w] ^ tw);
    }
    for (int b = 0; b < tailBytes; ++b)
      d += __builtin_popcount(static_cast<unsigned>(qTail[b] ^ t[words * 8 + b]));
    // As OpenCV's batchDistance: only a strictly better distance enters,
    // and it goes after the equal ones already kept.
    if (d >= bestDist[k - 1])
      continue;
    int s = k - 1;
    for (; s > 0 && bestDist[s - 1] > d; --s)
    {
      bestDist[s] = bestDist[s - 1];
      bestIdx[s] = bestIdx[s - 1];
    }
    bestDist[s] = d;
    bestIdx[s] = j;
  }
}
}  // namespace

std::vector<std::vector<cv::DMatch>> hammingKnn(const cv::Mat& query, const cv::Mat& train, int k)
{
  if (k < 1)
    throw std::invalid_argument("hammingKnn: k must be at least 1");
  std::vector<std::vector<cv::DMatch>> out(static_cast<std::size_t>(std::max(query.rows, 0)));
  if (query.empty() || train.empty())
    return out;
  if (query.type() != CV_8U || train.type() != CV_8U || query.cols != train.cols)
    throw std::invalid_argument("hammingKnn: descriptors must be CV_8U of the same width");
  const int words = query.cols / 8;
  if (words > 64)
    throw std::invalid_argument("hammingKnn: descriptors wider than 512 bytes");
  const int tailBytes = query.cols - words * 8;
  std::vector<int> dist(static_cast<std::size_t>(k)), idx(static_cast<std::size_t>(k));
  for (int i = 0; i < query.rows; ++i)
  {
    std::fill(dist.begin(), dist.end(), INT_MAX);
    std::fill(idx.begin(), idx.end(), -1);
    searchRow(query.ptr<std::uint8_t>(i), train, words, tailBytes, k, dist.data(), idx.data());
    auto& row = out[static_cast<std::size_t>(i)];
    for (int s = 0; s < k && idx[static_cast<std::size_t>(s)] >= 0; ++s)
      row.emplace_back(
          i, idx[static_cast<std::size_t>(s)], 0,
          static_cast<float>(dist[static_cast<std::size_t>(s)]));
  }
  return out;
}
}  // namespace roislam::matching
