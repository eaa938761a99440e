// L-inf distances from a point to a site.
#include <gtest/gtest.h>

#include <random>

#include "linf/geometry/distance.hpp"

using namespace linf;

TEST(Distance, PointAndSegment) {
  EXPECT_DOUBLE_EQ(dist_point(3, 4, 0, 0), 4);
  // Horizontal segment: vertical gap, or the corner beyond its end.
  EXPECT_DOUBLE_EQ(dist_segment(5, 3, {0, 0}, {10, 0}), 3);
  EXPECT_DOUBLE_EQ(dist_segment(14, 1, {0, 0}, {10, 0}), 4);
  // 45-degree segment: the L-inf distance from (0,10) to y=x is 5.
  EXPECT_DOUBLE_EQ(dist_segment(0, 10, {-100, -100}, {100, 100}), 5);
}

// Axis-parallel segments take a short cut (no divisions); it must agree with the minimum over
// densely sampled points of the segment, from below by at most the sampling step, and never
// exceed it, in every direction and on both sides, reversed segments included.
TEST(Distance, AxisParallelShortCutAgreesWithTheSegmentsPoints) {
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<int> c(-50, 50);
  for (int i = 0; i < 2000; ++i) {
    const Point a{c(rng), c(rng)};
    const int len = c(rng);
    const Point b = i % 2 ? Point{a.x + len, a.y} : Point{a.x, a.y + len};
    const double x = 1.5 * c(rng) + 0.25, y = 1.5 * c(rng) - 0.5;
    double brute = INFINITY;
    const int steps = 4000;
    for (int k = 0; k <= steps; ++k) {
      const double t = double(k) / steps;
      brute = std::min(brute, dist_point(x, y, double(a.x) + t * double(b.x - a.x), double(a.y) + t * double(b.y - a.y)));
    }
    const double d = dist_segment(x, y, a, b);
    EXPECT_LE(d, brute + 1e-12) << a.x << "," << a.y << " " << b.x << "," << b.y << " at " << x << "," << y;
    EXPECT_GE(d, brute - 100.0 / steps) << a.x << "," << a.y << " " << b.x << "," << b.y << " at " << x << "," << y;
  }
}
