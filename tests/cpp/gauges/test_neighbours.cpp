// Neighbouring spaces against brute force: every gauge asked about, the least cd of the other
// kind within the radius, on random gauges (points on a coarse grid, so that many lie exactly on
// the square's border and many cds tie), for 1 and 2 threads.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "linf/gauges/neighbours.hpp"

using namespace linf;

namespace {

double brute(const std::vector<SpacePoint>& g, std::size_t i, double r) {
  double best = std::numeric_limits<double>::infinity();
  const bool external = g[i].type == GaugeType::External;
  for (const SpacePoint& o : g) {
    const bool other = external ? o.type == GaugeType::Internal : o.type == GaugeType::External;
    if (other && std::fabs(o.x - g[i].x) <= r && std::fabs(o.y - g[i].y) <= r) best = std::min(best, o.cd);
  }
  return best;
}

}  // namespace

TEST(Neighbours, LeastCdOfTheOtherKindWithinTheRadius) {
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    std::mt19937_64 rng(seed);
    std::vector<SpacePoint> g(300);
    for (SpacePoint& p : g)
      p = {double(rng() % 60) * 5.0 - 100.0, double(rng() % 60) * 5.0 - 100.0, double(1 + rng() % 12),
           GaugeType(rng() % 5)};
    const double r = double(5 + rng() % 40);
    std::vector<std::int32_t> asked;
    for (std::int32_t i = 0; i < std::int32_t(g.size()); i += 1 + std::int32_t(rng() % 3)) asked.push_back(i);
    for (int threads : {1, 2}) {
      const std::vector<double> got = neighbouring_spaces(g, asked, r, threads);
      ASSERT_EQ(got.size(), asked.size());
      for (std::size_t q = 0; q < asked.size(); ++q) {
        const double want = brute(g, std::size_t(asked[q]), r);
        if (std::isinf(want)) EXPECT_TRUE(std::isnan(got[q])) << "seed " << seed << " gauge " << asked[q];
        else EXPECT_EQ(got[q], want) << "seed " << seed << " gauge " << asked[q] << " radius " << r;
      }
    }
  }
}

TEST(Neighbours, BadArgumentsThrow) {
  const std::vector<SpacePoint> g{{0, 0, 1, GaugeType::Internal}, {1, 0, 2, GaugeType::External}};
  EXPECT_THROW(neighbouring_spaces(g, {0}, 0.0), std::invalid_argument);
  EXPECT_THROW(neighbouring_spaces(g, {0}, std::nan("")), std::invalid_argument);
  EXPECT_THROW(neighbouring_spaces(g, {2}, 1.0), std::invalid_argument);
  EXPECT_EQ(neighbouring_spaces(g, {0, 1}, 1.0), (std::vector<double>{2, 1}));
}
