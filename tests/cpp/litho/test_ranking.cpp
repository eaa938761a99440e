// The ranking by printability (ranking.hpp), against the rule stated pairwise.
#include "linf/litho/ranking.hpp"

#include <gtest/gtest.h>

#include "litho_fixtures.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

using namespace linf;
using namespace linf::litho;
using litho_test::column;

TEST(Ranking, ReadGaugesByScoreThenTheUnreadInTableOrder) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::mt19937 rng(5);
  std::vector<double> score, cd;
  std::vector<std::uint8_t> fails;
  for (int i = 0; i < 3000; ++i) {
    const int kind = int(rng() % 5);  // measured, pinch, bridge, open (no edge in reach), not simulated
    const double s = double(rng() % 40) / 8;  // many ties
    score.push_back(kind == 4 ? nan : kind == 1 || kind == 2 ? -s / 10 : s);
    cd.push_back(kind == 0 ? 30 + s : kind == 1 || kind == 2 ? 0 : nan);
    fails.push_back(std::uint8_t(kind == 1 ? 1 : kind == 2 ? 2 : 0));
  }
  const Ranking r = rank_by_printability(column(score), column(cd), column(fails));
  const std::size_t n = score.size();
  ASSERT_EQ(r.order.size(), n);
  ASSERT_EQ(r.score.size(), n);
  auto read = [&](std::size_t i) { return !std::isnan(cd[i]) || fails[i] != 0; };
  std::size_t reads = 0;
  double top = -INFINITY;
  for (std::size_t i = 0; i < n; ++i)
    if (read(i)) ++reads, top = std::max(top, score[i]);
  EXPECT_EQ(r.read, reads);
  std::vector<bool> seen(n, false);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = std::size_t(r.order[k]);
    ASSERT_LT(i, n);
    EXPECT_FALSE(seen[i]);
    seen[i] = true;
    EXPECT_EQ(r.score[k], read(i) ? score[i] : top) << k;
    if (k == 0) continue;
    const std::size_t h = std::size_t(r.order[k - 1]);
    EXPECT_LE(r.score[k - 1], r.score[k]) << k;  // scores never decrease with rank
    EXPECT_FALSE(!read(h) && read(i)) << k;       // the read ones first
    if (read(h) == read(i) && (!read(i) || score[h] == score[i])) EXPECT_LT(h, i) << k;  // ties in table order
  }
  EXPECT_EQ(r.highest, top);
  EXPECT_GT(reads, n / 2);
  EXPECT_LT(reads, n);
}

TEST(Ranking, NothingReadKeepsTheTableOrderWithScoreOne) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> score{nan, 0.4, nan}, cd{nan, nan, nan};
  const std::vector<std::uint8_t> fails{0, 0, 0};
  const Ranking r = rank_by_printability(column(score), column(cd), column(fails));
  EXPECT_EQ(r.order, (std::vector<std::int32_t>{0, 1, 2}));
  EXPECT_EQ(r.score, (std::vector<double>{1, 1, 1}));
  EXPECT_EQ(r.read, 0u);
  EXPECT_EQ(r.highest, 1.0);
  EXPECT_THROW(rank_by_printability(column(score), column(std::vector<double>{1.0}), column(fails)), std::invalid_argument);
}
