// Who simulates and the printability's chunks (chunks.hpp), against plain loops over the rule.
#include "linf/litho/chunks.hpp"

#include <gtest/gtest.h>

#include "litho_fixtures.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

using namespace linf;
using namespace linf::litho;
using litho_test::column;

namespace {

struct Table {
  std::vector<double> cx, cy;
  std::vector<std::int32_t> type;
  std::vector<std::uint64_t> context;
};

// Points on a few rows, many repeated (several gauges on one point: gauges of two types across
// one feature), contexts shared by gauges of either type.
Table table(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  Table t;
  for (std::size_t i = 0; i < n; ++i) {
    if (i > 0 && rng() % 4 == 0) {
      t.cx.push_back(t.cx.back()), t.cy.push_back(t.cy.back());
    } else {
      t.cx.push_back(double(rng() % 200000) + 0.5 * (rng() % 2)), t.cy.push_back(double(rng() % 40000));
    }
    t.type.push_back(std::int32_t(rng() % 3));
    t.context.push_back(rng() % (n / 3 + 1));
  }
  return t;
}

}  // namespace

TEST(Chunks, TheFirstOfEachTypeAndContextSimulates) {
  const Table t = table(5000, 3);
  const Sources s = sources_of(column(t.type), column(t.context));
  ASSERT_EQ(s.source.size(), t.cx.size());
  std::vector<std::size_t> reps;
  for (std::size_t i = 0; i < t.cx.size(); ++i) {
    std::size_t first = i;
    for (std::size_t j = 0; j < i; ++j)
      if (t.type[j] == t.type[i] && t.context[j] == t.context[i]) {
        first = j;
        break;
      }
    EXPECT_EQ(s.source[i], first) << i;
    if (first == i) reps.push_back(i);
  }
  EXPECT_EQ(s.reps, reps);
  EXPECT_LT(reps.size(), t.cx.size());  // some gauges share a reading
  const Sources all = sources_of(column(t.type), Strided<std::uint64_t>{});
  EXPECT_EQ(all.reps.size(), t.cx.size());
  EXPECT_THROW(sources_of(column(t.type), column(std::vector<std::uint64_t>(3, 0))), std::invalid_argument);
}

TEST(Chunks, NearbyPointsTogetherEachPointInOneChunk) {
  for (const std::size_t wanted : {std::size_t(1), std::size_t(8), std::size_t(1000)}) {
    const Table t = table(40000, 7);
    const double band = 4096;
    const Chunks c = plan_chunks(column(t.cx), column(t.cy), column(t.type), column(t.context), band, wanted);
    const Sources s = sources_of(column(t.type), column(t.context));
    // Every simulating gauge once.
    std::vector<std::size_t> seen = c.gauges;
    std::sort(seen.begin(), seen.end());
    ASSERT_EQ(seen, s.reps) << wanted;
    ASSERT_EQ(c.starts.front(), 0u);
    ASSERT_EQ(c.starts.back(), c.gauges.size());
    const std::size_t size =
        std::max(kMinChunk, std::min(kMaxChunk, (s.reps.size() + wanted - 1) / wanted));
    std::set<std::pair<double, double>> points_before;
    for (std::size_t k = 0; k + 1 < c.starts.size(); ++k) {
      const std::size_t a = c.starts[k], b = c.starts[k + 1];
      ASSERT_LT(a, b);
      EXPECT_TRUE(std::is_sorted(c.gauges.begin() + std::ptrdiff_t(a), c.gauges.begin() + std::ptrdiff_t(b)));
      if (k + 2 < c.starts.size()) EXPECT_GE(b - a, size) << k;  // only the last may be short
      std::set<std::pair<double, double>> points;
      double lo = INFINITY, hi = -INFINITY;
      for (std::size_t j = a; j < b; ++j) {
        const std::size_t i = c.gauges[j];
        points.insert({t.cx[i], t.cy[i]});
        lo = std::min(lo, std::floor(t.cy[i] / band)), hi = std::max(hi, std::floor(t.cy[i] / band));
      }
      // Past the size only to keep a point's gauges together: the extra ones all on the point
      // just before the cut.
      if (b - a > size) {
        std::vector<std::size_t> by_key(c.gauges.begin() + std::ptrdiff_t(a), c.gauges.begin() + std::ptrdiff_t(b));
        std::sort(by_key.begin(), by_key.end(), [&](std::size_t p, std::size_t q) {
          const double bp = std::floor(t.cy[p] / band), bq = std::floor(t.cy[q] / band);
          return bp != bq ? bp < bq : t.cx[p] != t.cx[q] ? t.cx[p] < t.cx[q] : t.cy[p] != t.cy[q] ? t.cy[p] < t.cy[q] : p < q;
        });
        std::set<std::pair<double, double>> extra;
        for (std::size_t j = size - 1; j < by_key.size(); ++j) extra.insert({t.cx[by_key[j]], t.cy[by_key[j]]});
        EXPECT_EQ(extra.size(), 1u) << k;
      }
      for (const auto& p : points) EXPECT_EQ(points_before.count(p), 0u) << k;  // a point in one chunk
      points_before.insert(points.begin(), points.end());
      if (wanted == 1000) EXPECT_LE(hi - lo, 1.0) << k;  // small chunks span at most two bands
    }
    if (wanted == 1) EXPECT_EQ(c.starts.size() - 1, (s.reps.size() + kMaxChunk - 1) / kMaxChunk);
    // Each gauge finds its source's reading.
    ASSERT_EQ(c.at.size(), t.cx.size());
    for (std::size_t i = 0; i < t.cx.size(); ++i) EXPECT_EQ(c.gauges[c.at[i]], s.source[i]) << i;
  }
}

TEST(Chunks, BadInputIsRefused) {
  const Table t = table(100, 1);
  EXPECT_THROW(plan_chunks(column(t.cx), column(t.cy), column(t.type), column(t.context), 0, 4), std::invalid_argument);
  EXPECT_THROW(plan_chunks(column(t.cx), column(std::vector<double>(3)), column(t.type), column(t.context), 100, 4),
               std::invalid_argument);
  const Chunks none = plan_chunks(column(std::vector<double>{}), column(std::vector<double>{}), column(std::vector<std::int32_t>{}),
                                  Strided<std::uint64_t>{}, 100, 4);
  EXPECT_TRUE(none.gauges.empty());
  EXPECT_EQ(none.starts, std::vector<std::size_t>{0});
}
