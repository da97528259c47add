// Order statistics of measurements (benchmarks' frame times).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace refx {

// The q-quantile (0 <= q <= 1) of ascending, non-empty `sorted` by the nearest-rank
// method: the smallest value with at least a fraction q of the values at or below it
// (q = 0: the smallest value).
inline double nearestRank(const std::vector<double>& sorted, double q) {
  const size_t rank = size_t(std::ceil(q * double(sorted.size())));
  return sorted[std::clamp<size_t>(rank, 1, sorted.size()) - 1];
}

}  // namespace refx
