// Context ids (linf/gauges/context.hpp): the same neighbourhood moved, turned or mirrored has
// the same id; any change within the radius changes it; nothing outside does.
#include <gtest/gtest.h>

#include <random>
#include <set>

#include "linf/gauges/context.hpp"
#include "layouts.hpp"

using namespace linf;
using linf::testing::box;
using linf::testing::random_layout;
using linf::testing::Style;

namespace {

std::vector<std::uint64_t> ids(const std::vector<Polygon>& layout, const std::vector<double>& at, std::int64_t radius,
                               int threads = 1) {
  const PolygonArrays a = flat_of(layout);
  return context_ids(a.view(), at, radius, threads);
}

std::uint64_t id(const std::vector<Polygon>& layout, double x, double y, std::int64_t radius) {
  return ids(layout, {x, y}, radius)[0];
}

template <class F>
std::vector<Polygon> mapped(std::vector<Polygon> layout, F&& f) {
  for (Polygon& p : layout) {
    for (Point& v : p.outer) v = f(v);
    for (Ring& h : p.holes)
      for (Point& v : h) v = f(v);
  }
  return layout;
}

// Shapes of every kind (rectangles, L, frames with holes, 45-degree and any-angle), one to a
// cell of a grid so that none overlap: a merged layer.
std::vector<Polygon> mixed_layer(std::uint64_t seed) {
  std::vector<Polygon> out;
  const Style styles[] = {Style::Rectilinear, Style::Octilinear, Style::AnyAngle};
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i < 6; ++i) {
      const auto one = random_layout(seed * 100 + std::uint64_t(6 * j + i), styles[(i + j) % 3], 1, 120);
      for (const Polygon& p : one)
        out.push_back(mapped({p}, [&](Point v) { return Point{v.x + 260 * i, v.y + 260 * j}; })[0]);
    }
  return out;
}

// Points all over the layer, on integers and half-integers.
std::vector<double> points(std::uint64_t seed, int n) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> u(-100, 3300);
  std::vector<double> at;
  for (int i = 0; i < 2 * n; ++i) at.push_back(0.5 * u(rng));
  return at;
}

// The eight symmetries of the square about the origin.
Point symmetry(int t, Point v) {
  if (t & 1) std::swap(v.x, v.y);
  if (t & 2) v.x = -v.x;
  if (t & 4) v.y = -v.y;
  return v;
}

}  // namespace

TEST(Context, InvariantUnderTranslation) {
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<Coord> far(-(Coord(1) << 29), Coord(1) << 29);
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const auto layer = mixed_layer(seed);
    const auto at = points(seed, 300);
    const auto base = ids(layer, at, 150);
    EXPECT_GT(std::set<std::uint64_t>(base.begin(), base.end()).size(), 200u);  // the ids tell places apart
    for (int k = 0; k < 3; ++k) {
      const Coord dx = k == 0 ? 1 : far(rng), dy = k == 0 ? -3 : far(rng);
      std::vector<double> moved = at;
      for (std::size_t i = 0; i < moved.size(); i += 2) moved[i] += double(dx), moved[i + 1] += double(dy);
      EXPECT_EQ(ids(mapped(layer, [&](Point v) { return Point{v.x + dx, v.y + dy}; }), moved, 150), base)
          << "seed " << seed << " offset " << dx << ", " << dy;
    }
  }
}

TEST(Context, InvariantUnderTheSymmetriesOfTheSquare) {
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const auto layer = mixed_layer(seed);
    const auto at = points(seed + 10, 300);
    const auto base = ids(layer, at, 170);
    for (int t = 1; t < 8; ++t) {
      std::vector<double> moved = at;
      for (std::size_t i = 0; i < moved.size(); i += 2) {
        // Half-integer points: the symmetry applied to the doubled point.
        const Point p = symmetry(t, {Coord(2 * at[i]), Coord(2 * at[i + 1])});
        moved[i] = 0.5 * double(p.x), moved[i + 1] = 0.5 * double(p.y);
      }
      EXPECT_EQ(ids(mapped(layer, [&](Point v) { return symmetry(t, v); }), moved, 170), base) << "seed " << seed << " symmetry " << t;
    }
  }
}

TEST(Context, ThreadsGiveTheSameIds) {
  const auto layer = mixed_layer(3);
  const auto at = points(3, 2000);
  EXPECT_EQ(ids(layer, at, 90, 1), ids(layer, at, 90, 2));
}

TEST(Context, OneEdgeMovedByOneUnitWithinTheRadiusChangesTheId) {
  // A wire and its neighbour; the neighbour's near edge moves by 1 DBU at the window's far side.
  const std::vector<Polygon> a = {box(0, 0, 40, 1000), box(100, 0, 140, 1000)};
  const std::vector<Polygon> b = {box(0, 0, 40, 1000), box(99, 0, 140, 1000)};
  const std::vector<Polygon> c = {box(0, 0, 40, 1000), box(100, 0, 141, 1000)};  // far edge, outside
  const std::vector<Polygon> d = {box(0, 0, 40, 1000), box(100, 0, 140, 1000), box(0, 1030, 40, 1060)};
  EXPECT_NE(id(a, 20, 500, 100), id(b, 20, 500, 100));
  EXPECT_EQ(id(a, 20, 500, 100), id(c, 20, 500, 100));   // x = 141 is beyond 20 + 100
  EXPECT_NE(id(a, 20, 500, 130), id(c, 20, 500, 130));   // within a wider radius it counts
  EXPECT_EQ(id(a, 20, 500, 100), id(d, 20, 500, 100));   // a shape far above is outside
  EXPECT_NE(id(a, 20, 900, 131), id(d, 20, 900, 131));   // and inside when near
  // Any angle: one vertex of a triangle moved by one unit.
  const std::vector<Polygon> t1 = {{{{0, 0}, {70, 13}, {20, 61}}, {}}};
  const std::vector<Polygon> t2 = {{{{0, 0}, {70, 14}, {20, 61}}, {}}};
  EXPECT_NE(id(t1, 30, 30, 50), id(t2, 30, 30, 50));
}

TEST(Context, GeometryOutsideTheRadiusDoesNotCount) {
  const auto layer = mixed_layer(5);
  // Everything outside [1000 - r, 1000 + r]^2 replaced: kept only if it meets the window.
  const std::int64_t r = 200;
  std::vector<Polygon> near, changed;
  for (const Polygon& p : layer) {
    Coord x1 = p.outer[0].x, x2 = x1, y1 = p.outer[0].y, y2 = y1;
    for (const Point& v : p.outer) x1 = std::min(x1, v.x), x2 = std::max(x2, v.x), y1 = std::min(y1, v.y), y2 = std::max(y2, v.y);
    const bool meets = x2 >= 1000 - r && x1 <= 1000 + r && y2 >= 1000 - r && y1 <= 1000 + r;
    if (meets) near.push_back(p), changed.push_back(p);
    else changed.push_back(mapped({p}, [](Point v) { return Point{v.x + 7, v.y - 3}; })[0]);
  }
  ASSERT_FALSE(near.empty());
  ASSERT_LT(near.size(), layer.size());
  EXPECT_EQ(id(layer, 1000, 1000, r), id(near, 1000, 1000, r));
  EXPECT_EQ(id(layer, 1000, 1000, r), id(changed, 1000, 1000, r));
}

TEST(Context, IdenticalWiresOfAGratingHaveOneId) {
  std::vector<Polygon> grating;
  for (int i = 0; i < 9; ++i) grating.push_back(box(100 * i, 0, 100 * i + 45, 5000));
  const auto at = ids(grating, {422.5, 2500, 522.5, 2500, 522.5, 2700, 422.5, 4990, 472.5, 2500}, 260);
  EXPECT_EQ(at[0], at[1]);  // corresponding points of two wires (centres at half DBU)
  EXPECT_EQ(at[0], at[2]);  // along a wire, far from its ends
  EXPECT_NE(at[0], at[3]);  // near the end of the wires
  EXPECT_NE(at[0], at[4]);  // in the space between them
  EXPECT_NE(id(grating, 422.5, 2500, 260), id(grating, 422, 2500, 260));  // half DBU counts
}

TEST(Context, EmptyNeighbourhoodHasAFixedId) {
  const std::vector<Polygon> layer = {box(0, 0, 100, 100)};
  EXPECT_EQ(id(layer, 500, 500, 100), empty_context_id(100));
  EXPECT_EQ(id({}, 0, 0, 100), empty_context_id(100));
  EXPECT_EQ(id(layer, -301, 50, 300), empty_context_id(300));  // the box one unit beyond the border
  EXPECT_EQ(id(layer, -300, 50, 300), empty_context_id(300));  // its edge on the border: no area inside
  EXPECT_NE(id(layer, -299, 50, 300), empty_context_id(300));
  EXPECT_NE(empty_context_id(300), empty_context_id(301));
}

TEST(Context, ShapesAcrossTheBorderAreClippedExactly) {
  // A wire through the window is the same as one cut exactly at the window's border; cut one
  // unit short it is not.
  const std::vector<Polygon> through = {box(-1000, -20, 1000, 20)};
  const std::vector<Polygon> cut = {box(-100, -20, 100, 20)};
  const std::vector<Polygon> shorter = {box(-99, -20, 100, 20)};
  EXPECT_EQ(id(through, 0, 0, 100), id(cut, 0, 0, 100));
  EXPECT_NE(id(through, 0, 0, 100), id(shorter, 0, 0, 100));
  // The whole window in the layer: only the window's sides bound it.
  EXPECT_EQ(id({box(-1000, -1000, 1000, 1000)}, 0, 0, 100), id({box(-100, -100, 100, 100)}, 0, 0, 100));
  // 45 degrees and any angle: the same lines inside the window, different shapes outside (the
  // any-angle edges cross the border at rational points).
  const std::vector<Polygon> diamond = {{{{0, -500}, {500, 0}, {0, 500}, {-500, 0}}, {}}};
  const std::vector<Polygon> octagon = {{{{-30, -500}, {30, -500}, {500, -30}, {500, 30}, {30, 500}, {-30, 500}, {-500, 30}, {-500, -30}}, {}}};
  const std::vector<Polygon> kite = {{{{0, -500}, {800, 300}, {0, 500}, {-500, 0}}, {}}};
  EXPECT_EQ(id(diamond, 250, -250, 100), id(kite, 250, -250, 100));
  EXPECT_NE(id(diamond, 250, -250, 100), id(octagon, 250, -250, 100));
  const std::vector<Polygon> slant = {{{{-1000, -300}, {1000, 401}, {1000, 2000}, {-1000, 2000}}, {}}};
  const std::vector<Polygon> slant_longer = {{{{-3000, -1001}, {1000, 401}, {1000, 2000}, {-3000, 2000}}, {}}};
  EXPECT_EQ(id(slant, 7, 50, 100), id(slant_longer, 7, 50, 100));  // the same line, longer outside
  const std::vector<Polygon> slant_turned = {{{{-1000, -300}, {1000, 402}, {1000, 2000}, {-1000, 2000}}, {}}};
  EXPECT_NE(id(slant, 7, 50, 100), id(slant_turned, 7, 50, 100));
}

TEST(Context, RectanglesClippedByHandGiveTheSameIds) {
  // An independent clipper for rectangles: each box cut to the window in whole DBU.
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<Coord> u(0, 90);
  std::vector<Polygon> layer;
  for (int j = 0; j < 12; ++j)
    for (int i = 0; i < 12; ++i) {
      const Coord x = 100 * i + u(rng) / 3, y = 100 * j + u(rng) / 3;
      layer.push_back(box(x, y, x + 30 + u(rng) / 3, y + 30 + u(rng) / 3));  // apart: a merged layer
    }
  std::uniform_int_distribution<Coord> at(0, 1200);
  for (int k = 0; k < 200; ++k) {
    const Coord cx = at(rng), cy = at(rng), r = 20 + u(rng) * 3;
    std::vector<Polygon> cut;
    for (const Polygon& p : layer) {
      const Coord x1 = std::max(p.outer[0].x, cx - r), y1 = std::max(p.outer[0].y, cy - r);
      const Coord x2 = std::min(p.outer[2].x, cx + r), y2 = std::min(p.outer[2].y, cy + r);
      if (x1 < x2 && y1 < y2) cut.push_back(box(x1, y1, x2, y2));
    }
    EXPECT_EQ(id(layer, double(cx), double(cy), r), id(cut, double(cx), double(cy), r)) << cx << ", " << cy << " r " << r;
    if (!cut.empty()) {  // and one unit less of the first clipped box is another context
      Polygon& b = cut[0];
      for (Point& v : b.outer)
        if (v.x == b.outer[2].x) v.x -= 1;
      if (b.outer[2].x > b.outer[0].x) EXPECT_NE(id(layer, double(cx), double(cy), r), id(cut, double(cx), double(cy), r));
    }
  }
}

TEST(Context, TheRegionCountsNotHowItsRingsAreDrawn) {
  const std::vector<Polygon> plain = {box(0, 0, 100, 60)};
  // A vertex in the middle of an edge, a repeated vertex, another start, the other orientation.
  const std::vector<Polygon> redrawn = {{{{0, 0}, {40, 0}, {100, 0}, {100, 60}, {100, 60}, {0, 60}}, {}}};
  const std::vector<Polygon> turned = {{{{100, 60}, {100, 0}, {0, 0}, {0, 60}}, {}}};
  for (double x : {50.0, 80.5, 130.0})
    for (std::int64_t r : {20, 45, 200}) {
      EXPECT_EQ(id(plain, x, 30, r), id(redrawn, x, 30, r)) << x << " r " << r;
      EXPECT_EQ(id(plain, x, 30, r), id(turned, x, 30, r)) << x << " r " << r;
    }
}
