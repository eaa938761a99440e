// Pattern classes: drawn cases for each rule, and on random layers the two properties that make
// the clustering right whatever its filter skips: every window matches its representative, and
// no two representatives match (each checked here by brute force over the 8 symmetries).
#include <gtest/gtest.h>

#include <boost/polygon/polygon.hpp>

#include <random>

#include "layouts.hpp"
#include "linf/selection/pattern_classes.hpp"

using namespace linf;
using linf::testing::box;

namespace {
namespace bp = boost::polygon;
using Window = std::array<std::int64_t, 4>;

Window square(std::int64_t x, std::int64_t y, std::int64_t side) { return {x, y, x + side, y + side}; }

Polygon moved(const Polygon& p, Coord dx, Coord dy) {
  Polygon q = p;
  for (Point& v : q.outer) v.x += dx, v.y += dy;
  for (Ring& h : q.holes)
    for (Point& v : h) v.x += dx, v.y += dy;
  return q;
}

// An L of two boxes at (x, y), its foot `foot` long: not symmetric under any rotation or mirror.
std::vector<Polygon> ell(Coord x, Coord y, Coord foot) {
  return {box(x + 10, y + 10, x + 20, y + 60), box(x + 20, y + 10, x + 20 + foot, y + 20)};
}

// The clip of a window as a polygon set in doubled coordinates about its centre, under
// symmetry k (mirror x if k & 1, then k >> 1 quarter turns): the oracle's own construction.
bp::polygon_set_data<long long> clip(const std::vector<Polygon>& layer, const Window& w, int k) {
  using namespace bp::operators;
  bp::polygon_set_data<long long> s;
  for (const Polygon& p : layer) {
    std::vector<bp::point_data<long long>> v;
    for (const Point& q : p.outer) {
      long long u = 2 * q.x - (w[0] + w[2]), t = 2 * q.y - (w[1] + w[3]);
      if (k & 1) u = -u;
      for (int r = 0; r < (k >> 1); ++r) std::tie(u, t) = std::make_tuple(-t, u);
      v.emplace_back(u, t);
    }
    bp::polygon_data<long long> poly;
    poly.set(v.begin(), v.end());
    s.insert(poly);
  }
  const long long h = w[2] - w[0];
  s &= bp::rectangle_data<long long>(-h, -h, h, h);
  return s;
}

bool match_area(const std::vector<Polygon>& layer, const Window& a, const Window& b, double fraction) {
  using namespace bp::operators;
  const double window = 4.0 * double(a[2] - a[0]) * double(a[2] - a[0]);
  for (int k = 0; k < 8; ++k) {
    bp::polygon_set_data<long long> x = clip(layer, a, 0) ^ clip(layer, b, k);
    if (double(bp::area(x)) <= fraction * window) return true;
  }
  return false;
}

PatternClasses classify(const std::vector<Polygon>& layer, const std::vector<Window>& w, ClassRule rule) {
  const PolygonArrays flat = flat_of(layer);
  return classify_patterns(flat.view(), w, rule);
}
}  // namespace

TEST(PatternClasses, TranslatedRotatedAndMirroredCopiesAreOnePattern) {
  std::vector<Polygon> layer;
  std::vector<Window> windows;
  for (int k = 0; k < 8; ++k) {  // eight copies of an L, each under another symmetry
    std::vector<Polygon> l = ell(0, 0, 30);
    for (Polygon& p : l) {
      for (Point& v : p.outer) {
        Coord u = 2 * v.x - 70, t = 2 * v.y - 70;  // about the window's centre (35, 35)
        if (k & 1) u = -u;
        for (int r = 0; r < (k >> 1); ++r) std::tie(u, t) = std::make_tuple(-t, u);
        v = {(u + 70) / 2 + 1000 * k, (t + 70) / 2 + 500};
      }
      layer.push_back(p);
    }
    windows.push_back(square(1000 * k, 500, 70));
  }
  windows.push_back(square(20000, 20000, 70));  // an empty window: a pattern of its own
  ClassRule exact;
  exact.area_fraction = 0;
  const PatternClasses p = classify(layer, windows, exact);
  ASSERT_EQ(p.representative.size(), 2u);
  EXPECT_EQ(p.count[0], 8);
  EXPECT_EQ(p.count[1], 1);
  EXPECT_EQ(p.representative[1], 8);
  for (int k = 0; k < 8; ++k) EXPECT_EQ(p.of_window[std::size_t(k)], 0) << "symmetry " << k;
}

TEST(PatternClasses, ThresholdsOfEachRule) {
  // Two Ls whose feet differ by 1 DBU (the XOR: a 10 x 1 sliver, 10 DBU^2 of a 70 x 70 window),
  // and one whose foot is 8 DBU longer (80 DBU^2, 8 DBU wide).
  std::vector<Polygon> layer;
  for (const Coord foot : {30, 31, 38})
    for (const Polygon& p : ell(1000 * (foot - 30), 0, foot)) layer.push_back(p);
  const std::vector<Window> w{square(0, 0, 70), square(1000, 0, 70), square(8000, 0, 70)};
  const double window = 70.0 * 70.0;
  auto patterns = [&](ClassRule::By by, double fraction, std::int64_t edge) {
    ClassRule r;
    r.by = by, r.area_fraction = fraction, r.edge = edge;
    return classify(layer, w, r).representative.size();
  };
  EXPECT_EQ(patterns(ClassRule::Area, 0, 0), 3u);
  EXPECT_EQ(patterns(ClassRule::Area, 9.9 / window, 0), 3u);
  EXPECT_EQ(patterns(ClassRule::Area, 10.0 / window, 0), 2u);
  EXPECT_EQ(patterns(ClassRule::Area, 80.0 / window, 0), 1u);
  EXPECT_EQ(patterns(ClassRule::Edge, 0, 0), 3u);
  EXPECT_EQ(patterns(ClassRule::Edge, 0, 1), 2u);
  EXPECT_EQ(patterns(ClassRule::Edge, 0, 7), 2u);
  EXPECT_EQ(patterns(ClassRule::Edge, 0, 8), 1u);
}

TEST(PatternClasses, RandomLayersAgainstBruteForce) {
  // A repeated cell with small variations, and random shapes: each window matches its
  // representative, and no two representatives match, by the oracle above.
  std::mt19937_64 rng(11);
  auto u = [&](int lo, int hi) { return Coord(std::uniform_int_distribution<int>(lo, hi)(rng)); };
  std::size_t compared = 0, patterns = 0;
  for (int round = 0; round < 8; ++round) {
    std::vector<Polygon> layer = linf::testing::random_layout(std::uint64_t(round + 1), linf::testing::Style::Rectilinear, 8);
    std::vector<Window> windows;
    const double fraction = 0.01 * double(round % 4);
    for (int i = 0; i < 25; ++i) {
      const Coord x = 5000 + 400 * i, y = 5000;
      for (const Polygon& p : ell(x, y, 20 + u(0, 3))) layer.push_back(p);
      if (u(0, 2) == 0) layer.push_back(box(x + 40, y + 40, x + 40 + u(1, 5), y + 45));
      windows.push_back(square(x, y, 70));
    }
    for (int i = 0; i < 25; ++i) windows.push_back(square(u(0, 300), u(0, 300), 70));
    ClassRule r;
    r.area_fraction = fraction;
    const PatternClasses p = classify(layer, windows, r);
    ASSERT_EQ(p.of_window.size(), windows.size());
    compared += p.compared, patterns += p.representative.size();
    std::vector<std::int32_t> counted(p.count.size(), 0);
    for (std::size_t i = 0; i < windows.size(); ++i) {
      const std::int32_t k = p.of_window[i];
      ++counted[std::size_t(k)];
      const std::size_t rep = std::size_t(p.representative[std::size_t(k)]);
      ASSERT_LE(rep, i) << "round " << round << ": a representative after its window";
      EXPECT_TRUE(match_area(layer, windows[i], windows[rep], fraction)) << "round " << round << " window " << i;
    }
    EXPECT_EQ(counted, p.count) << "round " << round;
    for (std::size_t a = 0; a < p.representative.size(); ++a)
      for (std::size_t b = a + 1; b < p.representative.size(); ++b)
        EXPECT_FALSE(match_area(layer, windows[std::size_t(p.representative[b])],
                                windows[std::size_t(p.representative[a])], fraction))
            << "round " << round << ": patterns " << a << " and " << b << " match";
  }
  EXPECT_LT(patterns, 8u * 50u);  // the repeated cells did group
  EXPECT_GT(compared, 0u);
}
