// Ranking by printability (ranking.hpp). On a layer of millions of gauges this was Python's
// sort and loops over every gauge, serial work of the submitting host whether or not the
// simulations run elsewhere.
#include "linf/litho/ranking.hpp"

#include <algorithm>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace linf::litho {

Ranking rank_by_printability(const Strided<double>& score, const Strided<double>& printed_cd,
                             const Strided<std::uint8_t>& fails) {
  const std::size_t n = score.size();
  if (printed_cd.size() != n || fails.size() != n) throw std::invalid_argument("ranking: the columns have different lengths");
  if (n > std::size_t(std::numeric_limits<std::int32_t>::max())) throw std::invalid_argument("ranking: more than 2^31 - 1 gauges");
  Ranking r;
  std::vector<double> key(n);
  std::vector<bool> read(n);
  double top = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    const double cd = printed_cd[i];
    read[i] = cd == cd || fails[i] != 0;
    key[i] = read[i] ? score[i] : std::numeric_limits<double>::infinity();
    if (read[i]) ++r.read, top = std::max(top, score[i]);
  }
  if (r.read == 0) top = 1.0;
  r.order.resize(n);
  std::iota(r.order.begin(), r.order.end(), 0);
  std::stable_sort(r.order.begin(), r.order.end(), [&](std::int32_t a, std::int32_t b) { return key[std::size_t(a)] < key[std::size_t(b)]; });
  r.score.resize(n);
  r.highest = n ? -std::numeric_limits<double>::infinity() : 1.0;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = std::size_t(r.order[k]);
    r.score[k] = read[i] ? score[i] : top;
    r.highest = std::max(r.highest, r.score[k]);
  }
  return r;
}

}  // namespace linf::litho
