#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <cstdio>
#include <random>

#include "linf/builder.hpp"
#include "linf/classify.hpp"
#include "linf/csv.hpp"
#include "linf/diagram.hpp"
#include "linf/distance.hpp"
#include "linf/sites.hpp"
#include "layouts.hpp"

using namespace linf;
using linf::testing::box;

TEST(Distance, PointAndSegment) {
  EXPECT_DOUBLE_EQ(dist_point(3, 4, 0, 0), 4);
  // Horizontal segment: vertical gap, or the corner beyond its end.
  EXPECT_DOUBLE_EQ(dist_segment(5, 3, {0, 0}, {10, 0}), 3);
  EXPECT_DOUBLE_EQ(dist_segment(14, 1, {0, 0}, {10, 0}), 4);
  // 45-degree segment: the L-inf distance from (0,10) to y=x is 5.
  EXPECT_DOUBLE_EQ(dist_segment(0, 10, {-100, -100}, {100, 100}), 5);
}

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

TEST(Diagram, KindsOfTwoWires) {
  // Two 20-wide wires 30 apart: internal medial axes, one external stretch at clearance 15.
  Result r = voronoi_of_polygons({box(0, 0, 200, 20), box(0, 50, 200, 70)});
  ASSERT_TRUE(r.check.ok());
  int internal = 0, external = 0, adjacent = 0;
  bool mid_space = false, mid_wire = false;
  for (const Piece& p : r.diagram.pieces) {
    if (p.kind == PieceKind::Internal) ++internal;
    if (p.kind == PieceKind::External) ++external;
    if (p.kind == PieceKind::Adjacent) ++adjacent;
    if (p.kind == PieceKind::External && p.p.y == 35 && p.q.y == 35 && std::fabs(p.d1 - 15) < 1e-9) mid_space = true;
    if (p.kind == PieceKind::Internal && p.p.y == 10 && p.q.y == 10 && std::fabs(p.d1 - 10) < 1e-9) mid_wire = true;
  }
  EXPECT_GT(internal, 0);
  EXPECT_GT(external, 0);
  EXPECT_GT(adjacent, 0);
  EXPECT_TRUE(mid_space);
  EXPECT_TRUE(mid_wire);
}

TEST(Diagram, NotchInsideAU) {
  // A U shape: the space between its arms is a notch, not external.
  Result r = voronoi_of_polygons({{{{0, 0}, {100, 0}, {100, 100}, {80, 100}, {80, 20}, {20, 20}, {20, 100}, {0, 100}}, {}}});
  ASSERT_TRUE(r.check.ok());
  bool notch = false;
  for (const Piece& p : r.diagram.pieces) {
    EXPECT_NE(p.kind, PieceKind::External);
    if (p.kind == PieceKind::Notch && std::fabs(0.5 * (p.p.x + p.q.x) - 50) < 1e-9 && p.p.y > 20) notch = true;
  }
  EXPECT_TRUE(notch);
}

TEST(Diagram, TieRuleTwoPointsOnALine) {
  // Two points with the same y: the two-dimensional L-inf bisector is cut at x = 5.
  Result r = voronoi_of_sites({{0, 0}, {10, 0}}, {});
  ASSERT_TRUE(r.check.ok());
  ASSERT_EQ(r.diagram.pieces.size(), 1u);
  EXPECT_DOUBLE_EQ(r.diagram.pieces[0].p.x, 5);
  EXPECT_DOUBLE_EQ(r.diagram.pieces[0].q.x, 5);
}

TEST(Diagram, TieRuleSegmentAndEndpoint) {
  // Horizontal segment and its endpoints: the adjacent pieces are the perpendiculars x=0, x=10.
  Result r = voronoi_of_sites({}, {{{0, 0}, {10, 0}}});
  ASSERT_TRUE(r.check.ok());
  int adjacent = 0;
  for (const Piece& p : r.diagram.pieces) {
    EXPECT_EQ(p.kind, PieceKind::Adjacent);
    EXPECT_EQ(p.p.x, p.q.x);
    EXPECT_TRUE(p.p.x == 0 || p.p.x == 10);
    ++adjacent;
  }
  EXPECT_EQ(adjacent, 2);
}

TEST(Diagram, RaysClippedToEnlargedBox) {
  Result r = voronoi_of_polygons({box(0, 0, 100, 10), box(0, 40, 100, 50)});
  const Box& c = r.diagram.clip;
  EXPECT_DOUBLE_EQ(c.x1, -100);
  EXPECT_DOUBLE_EQ(c.x2, 200);
  EXPECT_DOUBLE_EQ(c.y1, -100);
  EXPECT_DOUBLE_EQ(c.y2, 150);
  bool reaches = false;
  for (const Piece& p : r.diagram.pieces) {
    for (const Vec2& v : {p.p, p.q}) {
      EXPECT_GE(v.x, c.x1); EXPECT_LE(v.x, c.x2); EXPECT_GE(v.y, c.y1); EXPECT_LE(v.y, c.y2);
      reaches |= v.x == c.x1 || v.x == c.x2;
    }
  }
  EXPECT_TRUE(reaches);
}

TEST(Builder, SameDiagramWithOneOrTwoWorkers) {
  // The top-level boxes are shared out to workers; the result must not depend on how.
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    Sites s = sites_of_polygons(merge_polygons(linf::testing::random_layout(seed, linf::testing::Style::Octilinear, 12)));
    BuildOptions one, two;
    one.threads = 1, two.threads = 2;
    auto key = [](std::vector<Piece> v) {
      std::vector<std::array<double, 6>> k;
      for (const Piece& p : v) {
        const bool flip = std::make_pair(p.q.x, p.q.y) < std::make_pair(p.p.x, p.p.y);
        const Vec2 a = flip ? p.q : p.p, b = flip ? p.p : p.q;
        k.push_back({double(p.a), double(p.b), a.x, a.y, b.x, b.y});
      }
      std::sort(k.begin(), k.end());
      return k;
    };
    const auto k1 = key(build_pieces(s, clip_box(s), one)), k2 = key(build_pieces(s, clip_box(s), two));
    ASSERT_EQ(k1.size(), k2.size()) << "seed " << seed;
    for (std::size_t i = 0; i < k1.size(); ++i)
      for (int j = 0; j < 6; ++j) ASSERT_NEAR(k1[i][j], k2[i][j], 1e-6) << "seed " << seed;
  }
}

TEST(Builder, FarFieldPassGivesTheOnePassDiagram) {
  // The far field (beyond the sites' bounding box) is built in a second pass from the owners
  // of the inner box's border only; the pieces must be those of one pass over the clip box,
  // up to how a piece crossing the border is cut.
  const linf::testing::Style styles[] = {linf::testing::Style::Rectilinear, linf::testing::Style::Octilinear,
                                         linf::testing::Style::AnyAngle};
  for (std::uint64_t seed = 1; seed <= 60; ++seed) {
    Sites s = sites_of_polygons(merge_polygons(linf::testing::random_layout(seed, styles[seed % 3], 10)));
    BuildOptions two_pass, one_pass;
    one_pass.far_field_pass = false;
    const Box clip = clip_box(s);
    // Total length per owner pair: robust to a piece being cut in two at the border.
    auto lengths = [](const std::vector<Piece>& v) {
      std::map<std::pair<int, int>, double> m;
      for (const Piece& p : v) m[{p.a, p.b}] += std::hypot(p.q.x - p.p.x, p.q.y - p.p.y);
      return m;
    };
    const auto a = lengths(build_pieces(s, clip, two_pass)), b = lengths(build_pieces(s, clip, one_pass));
    ASSERT_EQ(a.size(), b.size()) << "seed " << seed;
    for (auto ia = a.begin(), ib = b.begin(); ia != a.end(); ++ia, ++ib) {
      ASSERT_EQ(ia->first, ib->first) << "seed " << seed;
      ASSERT_NEAR(ia->second, ib->second, 1e-6 * (1 + ib->second)) << "seed " << seed;
    }
  }
}

// Where many sites are nearly parallel seen from far away, their distances differ by a constant
// smaller than a box, and only the dominance test (subdivision.hpp, dominated()) keeps the
// builder from cutting the empty field down to that constant. The work is counted, not timed:
// solved sites (the sum of the local solves' sizes) were 293,053 and 2,932,553 before it, 12,313
// and 159,460 with it.
namespace {
std::size_t solved_sites_of(const std::vector<Polygon>& polys) {
  const DiagramOptions opt;  // with the checker: throws if the diagram is wrong
  EXPECT_NO_THROW(voronoi_of_polygons(polys, opt));
  Sites s = sites_of_polygons(merge_polygons(polys));
  BuildStats st;
  build_pieces(s, clip_box(s), opt.build, &st);
  return st.solved_sites;
}
}  // namespace

TEST(Builder, TrackEndsSeenFromFarAway) {
  // 40 tracks of wires whose left ends lie within 40 DBU of each other.
  std::vector<Polygon> p;
  std::uint64_t r = 3;
  auto next = [&r](int n) { r = r * 6364136223846793005ULL + 1442695040888963407ULL; return int((r >> 33) % n); };
  for (int k = 0; k < 40; ++k)
    for (Coord x = next(40); x < 3000;) {
      const Coord w = 150 + next(1350);
      p.push_back(linf::testing::box(x, k * 100, x + w, k * 100 + 50));
      x += w + 50 + next(550);
    }
  const std::size_t n = solved_sites_of(p);
  RecordProperty("solved_sites", int(n));
  EXPECT_LT(n, 40000u);
}

// Inside a disk drawn with many vertices the regions are long diagonal strips from the rim to
// the axes: a quarter box keeps half of its box's sites, so quartering does not thin them out,
// it only multiplies the boxes (down to boxes as narrow as a strip). Such boxes are solved
// whole (subdivision.hpp, curved()). Counted in convex cells, the local solves' unit of work:
// 391,572 before, 59,432 with it, for about 1,540 pieces; and the checker passes, on the disk
// and on a ring (the disk with a hole, off centre).
namespace {
Ring regular(int n, double r, Coord cx = 0, Coord cy = 0) {
  Ring ring;
  for (int k = 0; k < n; ++k) {
    const double a = 2 * 3.14159265358979323846 * k / n;
    ring.push_back({cx + Coord(std::llround(r * std::cos(a))), cy + Coord(std::llround(r * std::sin(a)))});
  }
  return ring;
}
}  // namespace

TEST(Builder, ManySidedDisk) {
  const std::vector<Polygon> disk{{regular(1024, 1e6), {}}};
  EXPECT_NO_THROW(voronoi_of_polygons(disk, DiagramOptions{}));
  Ring hole = regular(512, 4e5, 120000, -70000);
  std::reverse(hole.begin(), hole.end());
  EXPECT_NO_THROW(voronoi_of_polygons({{regular(1024, 1e6), {hole}}}, DiagramOptions{}));
  Sites s = sites_of_polygons(merge_polygons(disk));
  BuildStats st;
  build_pieces(s, clip_box(s), BuildOptions{}, &st);
  RecordProperty("cells", int(st.cells));
  EXPECT_LT(st.cells, 150000u);
}

TEST(Builder, RowOfEqualBoxesFarFromOthers) {
  // From far away the row's bottom edges and corners tie in L-inf; L1 decides among them.
  std::vector<Polygon> p{linf::testing::box(0, 0, 10, 10), linf::testing::box(100000, 0, 100010, 10),
                         linf::testing::box(0, 90000, 10, 90010)};
  for (int i = 0; i < 6; ++i) p.push_back(linf::testing::box(50000 + 20 * i, 50000, 50010 + 20 * i, 50030));
  const std::size_t n = solved_sites_of(p);
  RecordProperty("solved_sites", int(n));
  EXPECT_LT(n, 700000u);
}

// A row of 25 boxes, 10 x 30 DBU at a 20 DBU pitch, and three boxes 40,000 DBU away. Along
// the 45-degree line from the row's corner, the bottom edges of the row's far boxes tie in
// L-inf with its corner on one side of the line only, so no single piece of their distance is
// above the corner's; they were kept, and the boxes cut small, all along the line (dominated(),
// covers()). Under the row the bottom edges tie in L-inf over the whole field; a box of 44 of
// them was solved whole, at the square of its sites, where halves thin them out
// (process_pruned(), halve_across_ties()). Cells 34,822 before, 4,224 with the first change
// alone, 6,581 with both; the local solves' sizes squared, their cost, 2,094,857, 1,570,761 and
// 805,461 (6,339 cells and 604,085 with every site a reference in small solves, below).
TEST(Builder, RowCornerSeenAlongTheDiagonal) {
  std::vector<Polygon> p{linf::testing::box(40000, 0, 40010, 10), linf::testing::box(0, 40000, 10, 40010),
                         linf::testing::box(40000, 40000, 40010, 40010)};
  for (int i = 0; i < 25; ++i) p.push_back(linf::testing::box(20 * i, 0, 20 * i + 10, 30));
  EXPECT_NO_THROW(voronoi_of_polygons(p, DiagramOptions{}));
  Sites s = sites_of_polygons(merge_polygons(p));
  BuildStats st;
  build_pieces(s, clip_box(s), BuildOptions{}, &st);
  RecordProperty("cells", int(st.cells));
  RecordProperty("solved_pairs", int(st.solved_pairs));
  EXPECT_LT(st.cells, 12000u);
  EXPECT_LT(st.solved_pairs, 1000000u);
}

// Tracks of wires 150-1,500 DBU long from near x = 0 to `length`, clipped at `cut`.
namespace {
std::vector<Polygon> cut_block(int tracks, Coord length, Coord cut) {
  std::vector<Polygon> p;
  std::uint64_t r = 5;
  auto next = [&r](int n) { r = r * 6364136223846793005ULL + 1442695040888963407ULL; return int((r >> 33) % n); };
  for (int k = 0; k < tracks; ++k)
    for (Coord x = next(400); x < std::min(length, cut);) {
      const Coord w = 150 + next(1350);
      p.push_back(linf::testing::box(x, k * 100, std::min(x + w, cut), k * 100 + 50));
      x += w + 50 + next(550);
    }
  return p;
}
}  // namespace

// Tracks cut on a vertical line, as the two-layouts experiment cuts a layer (check_halves.py):
// every track ends on the cut, and seen from the right all the ends tie in L-inf over the
// whole field; only L1 orders them, by the distance along the cut. Quartered, the boxes there
// stay a few tracks high out to the end of the field, so their number grew with the square of
// the tracks (subdivision.hpp, tie_axis()). Solved sites on 800 tracks: 2,112,810 before,
// 730,146 with long boxes cut across (the next test) only, 270,086 with the field's boxes
// halved along the cut.
TEST(Builder, TrackEndsAlignedOnACut) {
  const std::size_t n = solved_sites_of(cut_block(800, 1500, 1000));
  RecordProperty("solved_sites", int(n));
  EXPECT_LT(n, 400000u);
}

// A long layer (a row, a column, a slice): the tasks are cut from its box and are as long as
// it is, and quartering kept their shape down to the smallest boxes, each keeping the sites
// near any of its points. Long boxes are now cut across their length first (subdivision.hpp,
// process_pruned()). Solved sites on a column of 800 tracks, 1,500 DBU long: 970,080 before,
// 166,830 now.
TEST(Builder, LongLayerGetsSquareBoxes) {
  const std::size_t n = solved_sites_of(cut_block(800, 1500, Coord(1) << 30));
  RecordProperty("solved_sites", int(n));
  EXPECT_LT(n, 300000u);
}

// Two builds of the same sites give the same pieces: per owner pair, the same total length.
namespace {
std::map<std::pair<int, int>, double> pair_lengths(const Sites& s, const BuildOptions& opt, BuildStats& st) {
  std::map<std::pair<int, int>, double> by_pair;
  for (const Piece& q : build_pieces(s, clip_box(s), opt, &st)) by_pair[{q.a, q.b}] += std::hypot(q.q.x - q.p.x, q.q.y - q.p.y);
  return by_pair;
}
void expect_same_lengths(const std::map<std::pair<int, int>, double>& a, const std::map<std::pair<int, int>, double>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (auto ia = a.begin(), ib = b.begin(); ia != a.end(); ++ia, ++ib) {
    ASSERT_EQ(ia->first, ib->first);
    EXPECT_NEAR(ia->second, ib->second, 1e-6 * (1 + ia->second));
  }
}
}  // namespace

// Half the sites of the SRAM's local solves owned nothing in them: a far line end behind a
// near one, a corner behind an edge, each beaten by some other candidate that the one
// reference of the box is not. In local solves of at most BuildOptions::paired_sites sites
// every site is tried as the reference (subdivision.hpp, prune_dominated()). On a block of 40
// tracks: the same pieces (per owner pair, the same total length), far fewer solved sites.
TEST(Builder, EveryCandidateIsAReferenceInSmallBoxes) {
  const std::vector<Polygon> p = cut_block(40, 3000, Coord(1) << 30);
  Sites s = sites_of_polygons(merge_polygons(p));
  BuildOptions one;
  one.paired_sites = 0;
  BuildStats st_one, st_all;
  const auto a = pair_lengths(s, one, st_one), b = pair_lengths(s, BuildOptions{}, st_all);
  RecordProperty("solved_sites_one_reference", int(st_one.solved_sites));
  RecordProperty("solved_sites", int(st_all.solved_sites));
  EXPECT_LT(double(st_all.solved_sites), 0.8 * double(st_one.solved_sites));
  expect_same_lengths(a, b);
  EXPECT_NO_THROW(voronoi_of_polygons(p, DiagramOptions{}));  // the checker passes
}

// Where points and axis-parallel edges tie in L-inf, the L1 tie-break between two of them is
// the 1-D one between their extents across the shared piece's gradient: a half-plane at the
// midpoint of the gap, or the rank (Model::axis_order); along a region's edge, the owner
// beyond changes only at the gaps' midpoints (Model::axis_cuts), and is the nearest extent
// (Model::axis_owner). Without them those cells were cut by every L1 piece of the tied sites,
// the edges' L1 profiles walked and every tied site's functions evaluated for the owner
// beyond. The same pieces either way; on a block of 36 random Manhattan fields none of that
// is done any more; on a block with 45-degree shapes only where a slanted edge ties. And the
// checker passes.
TEST(Builder, ManhattanTiesAreHalfPlanes) {
  using linf::testing::Style;
  for (const Style style : {Style::Rectilinear, Style::Octilinear}) {
    const std::vector<Polygon> p = linf::testing::block(7, style, 6, 6);
    Sites s = sites_of_polygons(merge_polygons(p));
    BuildOptions general;
    general.axis_ties = false;
    BuildStats st_general, st_axis;
    const auto a = pair_lengths(s, general, st_general), b = pair_lengths(s, BuildOptions{}, st_axis);
    RecordProperty(style == Style::Rectilinear ? "tie_cells_general" : "tie_cells_general_45", int(st_general.tie_cells));
    RecordProperty(style == Style::Rectilinear ? "tie_cells" : "tie_cells_45", int(st_axis.tie_cells));
    RecordProperty(style == Style::Rectilinear ? "envelopes_general" : "envelopes_general_45", int(st_general.envelopes));
    RecordProperty(style == Style::Rectilinear ? "envelopes" : "envelopes_45", int(st_axis.envelopes));
    RecordProperty(style == Style::Rectilinear ? "owners_evaluated_general" : "owners_evaluated_general_45",
                   int(st_general.owners_evaluated));
    RecordProperty(style == Style::Rectilinear ? "owners_evaluated" : "owners_evaluated_45", int(st_axis.owners_evaluated));
    std::printf("%s: tie cells %zu -> %zu, envelopes %zu -> %zu, owners evaluated %zu -> %zu\n",
                style == Style::Rectilinear ? "rectilinear" : "octilinear", st_general.tie_cells, st_axis.tie_cells,
                st_general.envelopes, st_axis.envelopes, st_general.owners_evaluated, st_axis.owners_evaluated);
    EXPECT_GT(st_general.tie_cells, 0u);
    EXPECT_GT(st_general.envelopes, 0u);
    EXPECT_GT(st_general.owners_evaluated, 0u);
    if (style == Style::Rectilinear) {  // the owners beyond Manhattan ties from the extents alone
      EXPECT_EQ(st_axis.tie_cells, 0u);
      EXPECT_EQ(st_axis.envelopes, 0u);
      EXPECT_EQ(st_axis.owners_evaluated, 0u);
    } else {
      EXPECT_LT(st_axis.tie_cells, st_general.tie_cells);
      EXPECT_LT(st_axis.envelopes, st_general.envelopes);
      EXPECT_LT(st_axis.owners_evaluated, st_general.owners_evaluated);
    }
    expect_same_lengths(a, b);
    EXPECT_NO_THROW(voronoi_of_polygons(p, DiagramOptions{}));  // the checker passes
  }
}

// The CSV files' numbers are printf's "%.6f" (which the Python writer's bytes are compared
// with in the KLayout tests); the writer's own conversion must give the same text for every
// double, near-halves and signs included.
TEST(Csv, FixedSixAsPrintf) {
  std::mt19937_64 rng(11);
  std::vector<double> xs{0.0, -0.0, 1e-7, -1e-7, 4e-7, 5e-7, 6e-7, -5e-7, 0.0000015, 0.0000025, 2.5e-7, 999999.9999995,
                         1e9 - 0.0000005, 1e9, 1e12 + 0.5, -1e15, 1e300, INFINITY, -INFINITY, NAN};
  std::uniform_int_distribution<std::int64_t> coord(-(std::int64_t(1) << 31), std::int64_t(1) << 31);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int i = 0; i < 300000; ++i) {
    const std::int64_t k = coord(rng);
    xs.push_back(double(k) * 0.0025);                      // a site coordinate in micrometres
    xs.push_back(double(k) * 0.001 + unit(rng) * 1e-3);    // a piece's end
    xs.push_back((double(k) + 0.5) / 1e6);                 // near a half in the sixth place
    xs.push_back(std::ldexp(unit(rng) - 0.5, int(coord(rng) % 40)));
  }
  int differ = 0;
  for (double x : xs) {
    char want[512];
    std::snprintf(want, sizeof want, "%.6f", x);
    std::string got;
    linf::append_fixed6(got, x);
    if (got != want && ++differ <= 5) ADD_FAILURE() << x << ": " << got << " instead of " << want;
  }
  EXPECT_EQ(differ, 0);
}

// Plain input is held to the layout's range as polygons are (the checker indexes the sites'
// boxes in 32-bit integers).
TEST(Sites, PlainInputBeyondTheRangeIsRefused) {
  using linf::Point;
  EXPECT_THROW(linf::sites_of_plain({Point{Coord(1) << 31, 0}}, {}), std::invalid_argument);
  EXPECT_THROW(linf::sites_of_plain({}, {{Point{0, 0}, Point{0, -(Coord(1) << 30)}}}), std::invalid_argument);
  EXPECT_EQ(linf::sites_of_plain({Point{(Coord(1) << 30) - 1, 0}}, {}).sites.size(), 1u);
}
