// The layer cut to windows: where every polygon met is Manhattan the cut is made with
// Boost.Polygon's 90-degree sets, elsewhere with its general sets. Both must give the layer
// inside the window: checked here against the general set built in the test itself, on random
// layers whose rings are drawn badly on purpose (repeated and collinear points, any first edge,
// holes), and the 90-degree conversion of such rings on its own.
#include <gtest/gtest.h>

#include <boost/polygon/polygon.hpp>

#include <random>

#include "geometry/window_cut.hpp"
#include "layouts.hpp"

using namespace linf;
using linf::testing::Style;

namespace {
namespace bp = boost::polygon;

bp::polygon_data<long long> ring_of(const Ring& r) {
  std::vector<bp::point_data<long long>> v;
  for (const Point& p : r) v.emplace_back(p.x, p.y);
  return bp::polygon_data<long long>(v.begin(), v.end());
}

// The oracle: the layer & window with the general set, in 64-bit coordinates.
bp::polygon_set_data<long long> expected(const std::vector<Polygon>& layer, const std::array<std::int64_t, 4>& w) {
  using namespace bp::operators;
  bp::polygon_set_data<long long> s;
  for (const Polygon& p : layer) {
    bp::polygon_with_holes_data<long long> ph;
    const auto outer = ring_of(p.outer);
    ph.set(outer.begin(), outer.end());
    std::vector<bp::polygon_data<long long>> holes;
    for (const Ring& h : p.holes) holes.push_back(ring_of(h));
    ph.set_holes(holes.begin(), holes.end());
    s.insert(ph);
  }
  s &= bp::rectangle_data<long long>(w[0], w[1], w[2], w[3]);
  return s;
}

bp::polygon_set_data<long long> set_of(const std::vector<bp::polygon_data<int>>& cut) {
  bp::polygon_set_data<long long> s;
  for (const auto& q : cut) {
    std::vector<bp::point_data<long long>> v;
    for (const auto& p : q) v.emplace_back(p.x(), p.y());
    s.insert(bp::polygon_data<long long>(v.begin(), v.end()));
  }
  return s;
}

}  // namespace

TEST(WindowCut, ManhattanAndGeneralCutsAreTheLayerInsideTheWindow) {
  for (std::uint64_t seed = 1; seed <= 150; ++seed) {
    std::mt19937_64 rng(seed);
    const Style style = seed % 3 == 0 ? Style::Octilinear : Style::Rectilinear;
    std::vector<Polygon> layer = linf::testing::random_layout(seed, style, 8, 400);
    bool manhattan_layer = true;
    for (Polygon& p : layer) {
      const Ring outer = p.outer;
      for (std::size_t i = 0; i < outer.size(); ++i) {
        const Point& a = outer[i];
        const Point& b = outer[(i + 1) % outer.size()];
        if (a.x != b.x && a.y != b.y) manhattan_layer = false;
      }
      if (manhattan_layer || style == Style::Rectilinear) {
        // Midpoints only on axis-parallel edges, so the ring stays what it was.
        Ring r;
        const std::size_t start = std::size_t(rng() % outer.size());
        for (std::size_t i = 0; i < outer.size(); ++i) {
          const Point& a = outer[(start + i) % outer.size()];
          const Point& b = outer[(start + i + 1) % outer.size()];
          r.push_back(a);
          if (rng() % 3 == 0) r.push_back(a);
          if ((a.x == b.x || a.y == b.y) && rng() % 2 == 0) r.push_back({a.x == b.x ? a.x : (a.x + b.x) / 2,
                                                                         a.y == b.y ? a.y : (a.y + b.y) / 2});
        }
        p.outer = r;
      }
    }
    const PolygonArrays flat = flat_of(layer);
    const WindowCut cut(flat.view());
    for (int k = 0; k < 20; ++k) {
      const std::int64_t x = std::int64_t(rng() % 420) - 10, y = std::int64_t(rng() % 420) - 10,
                         side = std::int64_t(rng() % 200) + 1;
      const std::array<std::int64_t, 4> w{x, y, x + side, y + side};
      bool manhattan = false;
      const auto got = cut.cut(w, &manhattan);
      if (style == Style::Rectilinear) EXPECT_TRUE(manhattan) << "seed " << seed;
      using namespace bp::operators;
      const bp::polygon_set_data<long long> x_or = set_of(got) ^ expected(layer, w);  // a view would outlive its operands
      EXPECT_EQ(bp::area(x_or), 0) << "seed " << seed << " window " << x << ", " << y << " side " << side
                                   << (manhattan ? " (90-degree sets)" : " (general sets)");
    }
  }
}

TEST(WindowCut, RingsBecomeCompact90DegreePolygons) {
  // Started on a vertical edge, with a repeated point, a collinear point and a spike.
  const std::vector<bp::point_data<int>> ring{{0, 5}, {0, 0}, {0, 0}, {5, 0}, {10, 0}, {10, 10}, {10, 12},
                                              {10, 10}, {0, 10}};
  const auto q = polygon_90_of(ring);
  EXPECT_EQ(bp::area(q), 100);
  EXPECT_EQ(q.size(), 4u);
  const std::vector<bp::point_data<int>> flat{{0, 0}, {5, 0}, {10, 0}, {0, 0}};
  EXPECT_EQ(polygon_90_of(flat).size(), 0u);
}
