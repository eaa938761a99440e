// Pattern selection: the R-tree path against brute force, the coverage modes, the heuristic.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "linf/selection/selection.hpp"

using namespace linf;

namespace {
void expect_same(const Selection& a, const Selection& b, const char* what) {
  ASSERT_EQ(a.covered, b.covered) << what;
  ASSERT_EQ(a.used, b.used) << what;
  ASSERT_EQ(a.failed, b.failed) << what;
  ASSERT_EQ(a.redundant, b.redundant) << what;
  ASSERT_EQ(a.traversed, b.traversed) << what;
  ASSERT_EQ(a.windows.size(), b.windows.size()) << what;
  for (std::size_t i = 0; i < a.windows.size(); ++i) ASSERT_EQ(a.windows[i].markers, b.windows[i].markers) << what;
}
}  // namespace

TEST(Selection, RTreeAgreesWithBruteForce) {
  std::mt19937_64 rng(7);
  auto u = [&](int lo, int hi) { return double(std::uniform_int_distribution<int>(lo, hi)(rng)); };
  for (int round = 0; round < 300; ++round) {
    std::vector<Spot> spots;
    std::vector<Box> markers;
    const int n = int(u(1, 60)), m = int(u(1, 40));
    for (int i = 0; i < n; ++i) spots.push_back({{u(0, 200), u(0, 200)}, i});
    for (int i = 0; i < m; ++i) {
      const double x = u(0, 200), y = u(0, 200);
      // Points, boxes on the integer grid (so that borders coincide with windows), long bars.
      const int k = int(u(0, 2));
      const double w = k == 0 ? 0 : k == 1 ? u(1, 20) : u(30, 120), h = k == 0 ? 0 : u(1, 20);
      markers.push_back({x, y, x + w, y + h});
    }
    const double side = u(4, 60);
    for (Cover c : {Cover::Centre, Cover::Inside, Cover::Overlap})
      expect_same(select_windows(spots, markers, side, c), select_windows_brute(spots, markers, side, c), "mode");
  }
}

TEST(Selection, ModesOnOneWindow) {
  const Box w{0, 0, 10, 10};
  // A: strictly inside; a centre on the border does not count.
  EXPECT_TRUE(covers(w, {4, 4, 6, 6}, Cover::Centre));
  EXPECT_FALSE(covers(w, {10, 4, 10, 4}, Cover::Centre));
  // B: the whole marker, closed; C: any common point, closed.
  EXPECT_TRUE(covers(w, {0, 0, 10, 10}, Cover::Inside));
  EXPECT_FALSE(covers(w, {8, 8, 12, 9}, Cover::Inside));
  EXPECT_TRUE(covers(w, {8, 8, 12, 9}, Cover::Overlap));
  EXPECT_TRUE(covers(w, {10, 10, 12, 12}, Cover::Overlap));
  EXPECT_FALSE(covers(w, {11, 0, 12, 1}, Cover::Overlap));
}

TEST(Selection, UsedFailedRedundant) {
  // Gauge 0 covers marker 0, gauge 1 covers nothing, gauge 2 only marker 0 again, gauge 3
  // covers marker 1; then all markers are covered and gauge 4 is never looked at.
  const std::vector<Spot> spots{{{5, 5}, 0}, {{100, 100}, 1}, {{6, 6}, 2}, {{50, 5}, 3}, {{50, 6}, 4}};
  const std::vector<Box> markers{{5, 5, 5, 5}, {50, 5, 50, 5}};
  const Selection s = select_windows(spots, markers, 10, Cover::Centre);
  EXPECT_EQ(s.used, (std::vector<std::int32_t>{0, 3}));
  EXPECT_EQ(s.failed, (std::vector<std::int32_t>{1}));
  EXPECT_EQ(s.redundant, 1);
  EXPECT_EQ(s.traversed, 4);
  EXPECT_EQ(s.covered, 2);
  ASSERT_EQ(s.windows.size(), 2u);
  EXPECT_DOUBLE_EQ(s.windows[0].box.x1, 0);
  EXPECT_DOUBLE_EQ(s.windows[0].box.x2, 10);
}

TEST(Selection, HeuristicTakesTheBottommostPointFirst) {
  // Side 10: (0,0) opens [-1, 9]^2 covering (5,5) and (8,8); (20,1) opens its own; (3,12) too.
  const auto w = cover_points({{5, 5}, {3, 12}, {0, 0}, {20, 1}, {8, 8}}, 10);
  ASSERT_EQ(w.size(), 3u);
  EXPECT_DOUBLE_EQ(w[0].x1, -1);
  EXPECT_DOUBLE_EQ(w[0].y1, -1);
  EXPECT_DOUBLE_EQ(w[1].x1, 19);
  EXPECT_DOUBLE_EQ(w[2].y1, 11);
}

TEST(Selection, PitchOfAGrating) {
  // Lines 40 wide, spaces 60: pitch 100, whatever a few odd gauges and far-field spaces say.
  std::vector<std::pair<double, double>> widths{{40, 1000}, {40, 1000}, {40, 1000}, {25, 10}};
  std::vector<std::pair<double, double>> spaces{{60, 1000}, {60, 1000}, {3000, 50000}, {3000, 50000}};
  EXPECT_DOUBLE_EQ(estimate_pitch(widths, spaces), 100);
  EXPECT_DOUBLE_EQ(estimate_pitch({}, spaces), 0);
}

// The split's extra windows against the plain rule: in order, a point's window is kept when it
// overlaps (open boxes) none of the taken windows and none kept before it. Points on a coarse
// grid, so that windows often touch exactly, and negative coordinates for the grid's floor.
TEST(Selection, FreeWindowsAgreeWithBruteForce) {
  std::mt19937_64 rng(11);
  auto u = [&](int lo, int hi) { return double(std::uniform_int_distribution<int>(lo, hi)(rng)); };
  auto overlap = [](const Box& a, const Box& b) { return a.x1 < b.x2 && b.x1 < a.x2 && a.y1 < b.y2 && b.y1 < a.y2; };
  std::size_t kept_total = 0, dropped_total = 0;
  for (int round = 0; round < 300; ++round) {
    const double side = u(1, 4) * 10;
    std::vector<Box> taken;
    for (int i = 0, m = int(u(0, 10)); i < m; ++i) {
      const double x = u(-20, 20) * 5, y = u(-20, 20) * 5;
      taken.push_back({x, y, x + side, y + side});
    }
    std::vector<Vec2> points;
    for (int i = 0, n = int(u(1, 80)); i < n; ++i) points.push_back({u(-20, 20) * 5, u(-20, 20) * 5});
    std::vector<Box> all = taken;
    std::vector<std::int32_t> want;
    for (std::size_t k = 0; k < points.size(); ++k) {
      const Box b{points[k].x - side / 2, points[k].y - side / 2, points[k].x + side / 2, points[k].y + side / 2};
      if (std::none_of(all.begin(), all.end(), [&](const Box& o) { return overlap(b, o); })) {
        all.push_back(b);
        want.push_back(std::int32_t(k));
      }
    }
    ASSERT_EQ(free_windows(taken, points.data(), points.size(), side), want) << "round " << round;
    kept_total += want.size();
    dropped_total += points.size() - want.size();
  }
  EXPECT_GT(kept_total, 1000u);
  EXPECT_GT(dropped_total, 1000u);
}
