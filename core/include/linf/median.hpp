// The weighted median, shared by the gauges' typical width and the pitch estimate.
#pragma once
#include <algorithm>
#include <utility>
#include <vector>

namespace linf {

// The median of (value, weight) pairs by weight: the least value at which the accumulated
// weight reaches half the total. 0 if there is no weight.
inline double weighted_median(std::vector<std::pair<double, double>> v) {
  double total = 0;
  for (auto& p : v) total += p.second;
  if (total <= 0) return 0;
  std::sort(v.begin(), v.end());
  double acc = 0;
  for (auto& [x, w] : v)
    if ((acc += w) >= 0.5 * total) return x;
  return v.back().first;
}

}  // namespace linf
