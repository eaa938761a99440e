#pragma once
#include <algorithm>

namespace linf {

// A value with a weight (a width and the length it runs for). Plain, so that a layer's worth
// can sit in a Paged array.
struct Weighted {
  double value, weight;
};

// The median of `v` by weight: the least value at which the accumulated weight reaches half
// the total. 0 if there is no weight. Sorts `v` in place (a layer's widths are too many to copy).
template <class Range>
double weighted_median_in_place(Range& v) {
  double total = 0;
  for (const Weighted& p : v) total += p.weight;
  if (total <= 0) return 0;
  std::sort(v.begin(), v.end(), [](const Weighted& x, const Weighted& y) { return x.value < y.value; });
  double acc = 0;
  for (const Weighted& p : v)
    if ((acc += p.weight) >= 0.5 * total) return p.value;
  return (v.end() - 1)->value;
}

}  // namespace linf
