#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "linf/util/round.hpp"

namespace linf {
namespace {

TEST(Round, AgreesWithLlroundAtHalvesAndTheirNeighbours) {
  for (double h = -8.5; h <= 8.5; h += 0.5)
    for (double v : {h, std::nextafter(h, -100.0), std::nextafter(h, 100.0)})
      EXPECT_EQ(round_half_away(v), std::llround(v)) << v;
  // Where adding one half would round up first: 0.5 - 2^-54 is below one half.
  const double below_half = std::nextafter(0.5, 0.0);
  EXPECT_EQ(round_half_away(below_half), 0);
  EXPECT_EQ(round_half_away(-below_half), 0);
  for (double big : {std::ldexp(1.0, 52) + 1, std::ldexp(1.0, 52) - 0.5, std::ldexp(1.0, 53) + 2, std::ldexp(1.0, 62)})
    for (double v : {big, -big}) EXPECT_EQ(round_half_away(v), std::llround(v)) << v;
  // An absent score is infinite: it must sort where llround puts it.
  for (double v : {double(INFINITY), -double(INFINITY), std::ldexp(1.0, 70), -std::ldexp(1.0, 70)})
    EXPECT_EQ(round_half_away(v), std::llround(v)) << v;
}

TEST(Round, AgreesWithLlroundOnRandomScales) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> e(-30, 60);
  for (int i = 0; i < 200000; ++i) {
    const double v = std::ldexp(u(rng), e(rng));
    ASSERT_EQ(round_half_away(v), std::llround(v)) << v;
  }
}

}  // namespace
}  // namespace linf
