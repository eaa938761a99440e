// A layer merged into polygons and cut into sites.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

#include "linf/geometry/piece.hpp"
#include "linf/geometry/sites.hpp"
#include "layouts.hpp"

using namespace linf;
using linf::testing::box;

TEST(Merge, OverlapAndTouchBecomeOne) {
  auto m = merge_polygons({box(0, 0, 10, 10), box(5, 5, 20, 20), box(20, 0, 30, 10)});
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0].outer.size(), 12u);  // collinear vertices removed
}

// The layer is merged in groups of whole clusters of touching boxes: any group size gives the
// same polygons (rings, vertex order, order) as one scan over everything.
TEST(Merge, GroupsGiveTheSameAsOneScan) {
  std::vector<Polygon> in;
  std::uint64_t r = 12345;
  auto next = [&](int m) { r = r * 6364136223846793005ULL + 1442695040888963407ULL; return Coord((r >> 33) % std::uint64_t(m)); };
  for (int i = 0; i < 3000; ++i) {
    const Coord x = next(20000), y = next(20000), w = 5 + next(300), h = 5 + next(300);
    in.push_back(box(x, y, x + w, y + h));
  }
  Polygon ring = box(30000, 0, 31000, 1000);  // a hole, and a box inside it touching nothing
  ring.holes.push_back({{30100, 100}, {30100, 900}, {30900, 900}, {30900, 100}});
  in.push_back(ring);
  in.push_back(box(30400, 400, 30600, 600));
  in.push_back({{{40000, 0}, {41000, 0}, {40500, 700}}, {}});  // slanted edges crossing a box
  in.push_back(box(40400, 300, 40600, 900));
  const auto whole = merge_polygons(in, in.size(), 1);
  ASSERT_LT(whole.size(), in.size());  // some merged
  // Groups of 1, 7 and 500 polygons one after the other; one group merged in 2 and 3 parts side by side.
  for (auto [group, threads] : {std::pair{std::size_t(1), 1}, {std::size_t(7), 1}, {std::size_t(500), 2},
                                {in.size(), 2}, {in.size(), 3}}) {
    const auto parts = merge_polygons(in, group, threads);
    ASSERT_EQ(parts.size(), whole.size()) << group;
    for (std::size_t i = 0; i < whole.size(); ++i) {
      ASSERT_EQ(parts[i].outer, whole[i].outer) << group << " polygon " << i;
      ASSERT_EQ(parts[i].holes, whole[i].holes) << group << " polygon " << i;
    }
  }
}

// A plain polygon (no holes, a clean and simple outline) that meets no other is taken as it
// is, without Boost.Polygon's scan, and must come out as the scan gives it: the same ring from
// the same vertex. The reference is the layer with a frame far around it: the frame has a hole,
// so it is not plain, and its box meets every polygon's, so everything goes through one scan
// whatever the test of plain polygons decides. But the scan cuts edges that are slanted other
// than at 45 degrees at other edges' events, rounding the cuts to the grid, so where a layer
// has such edges the frame would move them: there each polygon is doubled instead (it meets
// its copy, and their union is itself), which is a scan of each alone. Compared on single rings
// that are plain (merged outlines, stars at any angle, in either direction, from any vertex)
// and that are not (crossing or touching themselves, repeated points, vertices on a straight
// line), on random layouts, and on polygons whose boxes overlap where they meet or do not
// (nested without touching, interleaved, touching at a corner or along an edge, inside a
// hole, around a comb).
TEST(Merge, PlainPolygonsAloneAreTheirOwnMerge) {
  std::mt19937_64 rng(7);
  auto u = [&](Coord lo, Coord hi) { return std::uniform_int_distribution<Coord>(lo, hi)(rng); };
  std::vector<std::vector<Polygon>> layers;
  for (std::uint64_t seed = 0; seed < 60; ++seed) {
    const auto layout = linf::testing::random_layout(seed, linf::testing::Style(seed % 3), 8);
    layers.push_back(layout);
    for (const Polygon& p : merge_polygons(layout)) layers.push_back({p});
  }
  const double pi = std::acos(-1.0);
  for (int i = 0; i < 300; ++i) {
    const int n = int(u(3, 14));
    Ring r;
    if (i % 3 == 0) {  // random points: mostly crossing themselves
      for (int k = 0; k < n; ++k) r.push_back({u(0, 100), u(0, 100)});
    } else {  // a star at any angle: simple, unless rounding puts two points together
      for (int k = 0; k < n; ++k) {
        const double a = 2 * pi * (k + 0.1 * double(u(0, 9))) / n, rad = double(u(20, 400));
        r.push_back({Coord(std::lround(rad * std::cos(a))), Coord(std::lround(rad * std::sin(a)))});
      }
    }
    layers.push_back({{r, {}}});
  }
  layers.push_back({{{{0, 0}, {10, 0}, {10, 10}, {5, 0}, {0, 10}}, {}}});    // touches itself on an edge
  layers.push_back({{{{0, 0}, {10, 0}, {10, 10}, {0, 10}, {0, 10}}, {}}});   // a repeated point
  layers.push_back({{{{0, 0}, {5, 0}, {10, 0}, {10, 10}, {0, 10}}, {}}});    // a vertex on a straight edge
  layers.push_back({{{{0, 0}, {4, 0}, {4, 4}, {8, 4}, {8, 8}, {4, 8}, {4, 4}, {0, 4}}, {}}});  // a figure of eight
  const Polygon L1{{{0, 0}, {30, 0}, {30, 5}, {5, 5}, {5, 30}, {0, 30}}, {}};
  const Polygon L2{{{30, 30}, {8, 30}, {8, 25}, {25, 25}, {25, 8}, {30, 8}}, {}};
  layers.push_back({L1, L2});                                          // interleaved, apart
  layers.push_back({L1, box(10, 10, 20, 20)});                         // in the other's box, apart
  layers.push_back({box(0, 0, 100, 100), box(10, 10, 20, 20)});        // nested, not touching
  layers.push_back({box(0, 0, 10, 10), box(10, 10, 20, 20)});          // touching at a corner
  layers.push_back({L1, box(5, 5, 9, 9)});                             // touching at the inner corner
  layers.push_back({box(0, 0, 10, 10), box(10, 5, 20, 15)});           // sharing part of an edge
  for (int k = 0; k < 4; ++k) layers.push_back({box(0, 0, 10, 10), box(10, 2, 20, 8)});  // from each vertex
  layers.push_back({box(0, 0, 10, 10), {{{10, 5}, {20, 0}, {20, 10}}, {}}});  // a vertex on an edge
  Polygon frame = box(0, 0, 100, 100);
  frame.holes.push_back({{10, 10}, {10, 90}, {90, 90}, {90, 10}});
  layers.push_back({frame, box(30, 30, 60, 60)});                      // inside a hole
  // A comb of 30 teeth (120 points: its edges are indexed): boxes between its teeth, apart
  // and touching, on a tooth, over it all; the comb with a vertex moved (crossing itself).
  Polygon comb{{{0, 0}, {590, 0}}, {}};
  for (Coord t = 29; t >= 0; --t) {
    const Coord x = 20 * t;
    comb.outer.insert(comb.outer.end(), {{x + 10, 100}, {x, 100}});
    if (t > 0) comb.outer.insert(comb.outer.end(), {{x, 10}, {x - 10, 10}});
  }
  layers.push_back({comb, box(13, 20, 17, 90), box(33, 40, 37, 60)});   // between teeth, apart
  layers.push_back({comb, box(10, 20, 20, 90)});                       // filling a gap, touching
  layers.push_back({comb, box(42, 100, 48, 120)});                     // on a tooth's end
  layers.push_back({comb, box(-5, 50, 15, 55)});                       // across a tooth
  layers.push_back({comb, box(2, 20, 8, 90)});                         // inside a tooth
  layers.push_back({comb, box(-50, -50, 700, 200)});                   // covering it
  Polygon crossing = comb;
  crossing.outer[2] = {565, 50};
  layers.push_back({crossing, box(13, 20, 17, 90)});
  constexpr Coord kFar = 100000;
  Polygon far = box(-kFar, -kFar, kFar, kFar);
  far.holes.push_back({{1 - kFar, 1 - kFar}, {1 - kFar, kFar - 1}, {kFar - 1, kFar - 1}, {kFar - 1, 1 - kFar}});
  auto octilinear = [](const Ring& r) {
    for (std::size_t k = 0; k < r.size(); ++k) {
      const Point a = r[k], b = r[(k + 1) % r.size()];
      const Coord dx = b.x - a.x, dy = b.y - a.y;
      if (dx != 0 && dy != 0 && dx != dy && dx != -dy) return false;
    }
    return true;
  };
  std::size_t plain_alone = 0;
  for (std::size_t i = 0; i < layers.size(); ++i) {
    std::vector<Polygon> in = layers[i];
    for (Polygon& p : in) {
      if (i % 2) std::reverse(p.outer.begin(), p.outer.end());
      std::rotate(p.outer.begin(), p.outer.begin() + long(i % p.outer.size()), p.outer.end());
    }
    bool framed = true;
    std::vector<Polygon> reference;
    for (const Polygon& p : in) framed = framed && octilinear(p.outer);
    for (const Polygon& p : in) {
      reference.push_back(p);
      if (!framed) reference.push_back(p);
    }
    if (framed) reference.push_back(far);
    const auto merged = merge_polygons(in);
    auto scanned = merge_polygons(reference);
    if (framed) {
      ASSERT_EQ(scanned[0].outer.front(), (Point{kFar, kFar})) << i;  // the frame: the least vertex
      scanned.erase(scanned.begin());
    }
    ASSERT_EQ(merged.size(), scanned.size()) << i;
    for (std::size_t k = 0; k < merged.size(); ++k) {
      ASSERT_EQ(merged[k].outer, scanned[k].outer) << i;
      ASSERT_EQ(merged[k].holes, scanned[k].holes) << i;
    }
    plain_alone += in.size() == 1 && merged.size() == 1 && merged[0].outer.size() == in[0].outer.size();
  }
  EXPECT_GT(plain_alone, layers.size() / 3);  // many rings are plain
}

TEST(Merge, HoleKeptAndOriented) {
  Polygon p = box(0, 0, 100, 100);
  p.holes.push_back({{10, 10}, {10, 90}, {90, 90}, {90, 10}});
  auto m = merge_polygons({p});
  ASSERT_EQ(m.size(), 1u);
  ASSERT_EQ(m[0].holes.size(), 1u);
  Sites s = sites_of_polygons(m);
  // Interior is left of every edge: the point (5, 50) is inside, (50, 50) in the hole is not.
  for (const Site& t : s.sites) {
    if (t.is_point()) continue;
    const double cx = 0.5 * double(t.a.x + t.b.x), cy = 0.5 * double(t.a.y + t.b.y);
    const double dx = double(t.b.x - t.a.x), dy = double(t.b.y - t.a.y);
    const Vec2 left{cx - dy * 0.01, cy + dx * 0.01};
    const bool in_ring = left.x > 0 && left.x < 100 && left.y > 0 && left.y < 100 &&
                         !(left.x > 10 && left.x < 90 && left.y > 10 && left.y < 90);
    EXPECT_TRUE(in_ring) << t.a.x << "," << t.a.y << " -> " << t.b.x << "," << t.b.y;
  }
}

// Plain input is held to the layout's range as polygons are (the checker indexes the sites'
// boxes in 32-bit integers).
TEST(Sites, PlainInputBeyondTheRangeIsRefused) {
  using linf::Point;
  EXPECT_THROW(linf::sites_of_plain({Point{Coord(1) << 31, 0}}, {}), std::invalid_argument);
  EXPECT_THROW(linf::sites_of_plain({}, {{Point{0, 0}, Point{0, -(Coord(1) << 30)}}}), std::invalid_argument);
  EXPECT_EQ(linf::sites_of_plain({Point{(Coord(1) << 30) - 1, 0}}, {}).sites.size(), 1u);
}
