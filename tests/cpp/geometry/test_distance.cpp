// L-inf distances from a point to a site.
#include <gtest/gtest.h>

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
