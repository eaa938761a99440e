// Marching squares (contour.hpp): a disc's contour lies on its circle and closes; a saddle
// splits by its mean; bad grids are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>
#include <vector>

#include "linf/litho/contour.hpp"

using namespace linf::litho;

// A cone falling from 1 at (20, 20) by 0.05 a unit: the 0.52 level is the circle of radius 9.6,
// through no grid point.
TEST(Contour, ACircleIsClosedAndOnItsRadius) {
  const int m = 40;
  std::vector<double> v(m * m);
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) v[std::size_t(j * m + i)] = 1 - 0.05 * std::hypot(i - 20.0, j - 20.0);
  const std::vector<double> s = contour_segments(v, m, 0, m, 0.52);
  ASSERT_EQ(s.size() % 4, 0u);
  ASSERT_GT(s.size() / 4, 40u);
  std::map<std::pair<long, long>, int> ends;  // each end is shared by exactly two segments
  for (std::size_t k = 0; k < s.size(); k += 2) {
    // linear interpolation of a cone along a cell's side: within a few hundredths of the circle
    EXPECT_NEAR(std::hypot(s[k] - 20, s[k + 1] - 20), 9.6, 0.05) << k;
    ++ends[{std::lround(s[k] * 1e6), std::lround(s[k + 1] * 1e6)}];
  }
  for (const auto& [p, n] : ends) EXPECT_EQ(n, 2) << p.first << " " << p.second;
  // Only the cells [lo, hi - 1): a window off the circle has nothing, one across it some.
  EXPECT_TRUE(contour_segments(v, m, 0, 8, 0.52).empty());
  EXPECT_FALSE(contour_segments(v, m, 8, 16, 0.52).empty());
}

// One cell, corners 1, 0, 1, 0 (inside, outside alternately): a mean above the level joins the
// inside corners (two segments cutting off the outside ones), below it the outside ones.
TEST(Contour, SaddleSplitsByTheMean) {
  const std::vector<double> v{1, 0, 0, 1};  // (0,0)=1 (1,0)=0 (0,1)=0 (1,1)=1
  const std::vector<double> high = contour_segments(v, 2, 0, 2, 0.4), low = contour_segments(v, 2, 0, 2, 0.6);
  ASSERT_EQ(high.size(), 8u);
  ASSERT_EQ(low.size(), 8u);
  // Mean 0.5 >= 0.4: corner (0, 0) is joined to (1, 1); the segments cut off (1, 0) and (0, 1).
  EXPECT_EQ(high, (std::vector<double>{0.6, 0, 1, 0.4, 0.4, 1, 0, 0.6}));
  // Mean 0.5 < 0.6: the segments cut off (0, 0) and (1, 1).
  EXPECT_EQ(low, (std::vector<double>{0.4, 0, 0, 0.4, 1, 0.6, 0.6, 1}));
  EXPECT_THROW(contour_segments(v, 3, 0, 2, 0.5), std::invalid_argument);
  EXPECT_THROW(contour_segments(v, 2, 0, 3, 0.5), std::invalid_argument);
}
