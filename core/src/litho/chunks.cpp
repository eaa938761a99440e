// Simulating gauges and their chunks (chunks.hpp). On a layer of millions of gauges this was
// the submitting host's Python sort of position tuples: seconds of its CPU beside the workers.
#include "linf/litho/chunks.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <utility>

namespace linf::litho {

Sources sources_of(const Strided<std::int32_t>& type, const Strided<std::uint64_t>& context) {
  const std::size_t n = type.size();
  if (context.size() != 0 && context.size() != n) throw std::invalid_argument("printability: the context ids are not one a gauge");
  Sources s;
  s.source.resize(n);
  if (context.size() == 0) {
    std::iota(s.source.begin(), s.source.end(), std::size_t(0));
    s.reps = s.source;
    return s;
  }
  // Grouped by (context, type) with a sort, not a hash map of millions of small vectors: the
  // first of a group (the least number) is its source.
  struct Entry {
    std::uint64_t context;
    std::int32_t type;
    std::size_t i;
  };
  std::vector<Entry> e(n);
  for (std::size_t i = 0; i < n; ++i) e[i] = {context[i], type[i], i};
  std::sort(e.begin(), e.end(), [](const Entry& a, const Entry& b) {
    if (a.context != b.context) return a.context < b.context;
    if (a.type != b.type) return a.type < b.type;
    return a.i < b.i;
  });
  for (std::size_t k = 0; k < n; ++k) {
    const bool first = k == 0 || e[k].context != e[k - 1].context || e[k].type != e[k - 1].type;
    s.source[e[k].i] = first ? e[k].i : s.source[e[k - 1].i];
  }
  for (std::size_t i = 0; i < n; ++i)
    if (s.source[i] == i) s.reps.push_back(i);
  return s;
}

Chunks plan_chunks(const Strided<double>& cx, const Strided<double>& cy, const Strided<std::int32_t>& type,
                   const Strided<std::uint64_t>& context, double band, std::size_t wanted) {
  const std::size_t n = type.size();
  if (cx.size() != n || cy.size() != n) throw std::invalid_argument("printability chunks: the columns have different lengths");
  if (!(band > 0) || !std::isfinite(band)) throw std::invalid_argument("printability chunks: the band must be a positive number");
  const Sources s = sources_of(type, context);
  struct Key {
    double band, x, y;
    std::size_t i;
  };
  std::vector<Key> keys;
  keys.reserve(s.reps.size());
  for (const std::size_t i : s.reps) keys.push_back({std::floor(cy[i] / band), cx[i], cy[i], i});
  std::sort(keys.begin(), keys.end(), [](const Key& a, const Key& b) {
    if (a.band != b.band) return a.band < b.band;
    if (a.x != b.x) return a.x < b.x;
    if (a.y != b.y) return a.y < b.y;
    return a.i < b.i;
  });
  const std::size_t m = keys.size();
  const std::size_t per = (m + std::max<std::size_t>(wanted, 1) - 1) / std::max<std::size_t>(wanted, 1);
  const std::size_t size = std::max(kMinChunk, std::min(kMaxChunk, per));
  Chunks c;
  c.gauges.reserve(m);
  c.starts.push_back(0);
  for (std::size_t from = 0; from < m;) {
    std::size_t to = std::min(from + size, m);
    while (to < m && keys[to].x == keys[to - 1].x && keys[to].y == keys[to - 1].y) ++to;
    for (std::size_t k = from; k < to; ++k) c.gauges.push_back(keys[k].i);
    std::sort(c.gauges.begin() + std::ptrdiff_t(from), c.gauges.end());
    c.starts.push_back(to);
    from = to;
  }
  std::vector<std::size_t> where(n, 0);
  for (std::size_t k = 0; k < m; ++k) where[c.gauges[k]] = k;
  c.at.resize(n);
  for (std::size_t i = 0; i < n; ++i) c.at[i] = where[s.source[i]];
  return c;
}

}  // namespace linf::litho
