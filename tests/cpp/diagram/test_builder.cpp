// The builder: the same pieces however the work is shared out, and bounds on the work it does.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include "linf/diagram/builder.hpp"
#include "linf/diagram/diagram.hpp"
#include "linf/geometry/sites.hpp"
#include "diagram/join.hpp"
#include "layouts.hpp"

using namespace linf;

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

// Where two sites' L1 pieces change hands on nearly the same line (a slanted edge and its own
// end, whose pieces are rounded), the cells are cut into a sliver between the two lines, and
// a Voronoi edge along it is cut out from both sides of the sliver: the join must keep one
// piece of such copies, not join a piece to its own copy end to end (which left nothing).
TEST(Builder, SlantedEdgeAlone) {
  for (const bool far_field : {true, false}) {
    DiagramOptions o;
    o.build.threads = 1, o.build.far_field_pass = far_field;
    EXPECT_NO_THROW(voronoi_of_sites({}, {Segment{{36866, 49921}, {2, 51197}}}, o)) << "far field " << far_field;
  }
}

TEST(Builder, ParallelogramOfSmallSlope) {
  const std::vector<Polygon> p{Polygon{{{0, 0}, {35072, 2}, {35072, 1002}, {0, 1000}}, {}}};
  for (const bool far_field : {true, false}) {
    DiagramOptions o;
    o.build.threads = 1, o.build.far_field_pass = far_field;
    EXPECT_NO_THROW(voronoi_of_polygons(p, o)) << "far field " << far_field;
  }
}

// Segments fanning out of (32, 0), found by the fuzzer: left of x = 32 all of them tie in L-inf
// and the L1 tie-break gives the steep one a wedge of the far field, although at the inner
// box's border it loses every point to the short vertical one. The far field must take the
// sites tied at the border, not only its owners (far_field.hpp); the checker failed before.
TEST(Builder, FarFieldWedgeOfAnL1TieBreak) {
  const std::vector<Segment> fan{Segment{{32, 0}, {34, 55}}, Segment{{32, 0}, {32, 3}}, Segment{{32, 6}, {34, 177}},
                                 Segment{{32, 0}, {83, 4}}};
  for (const bool far_field : {true, false}) {
    DiagramOptions o;
    o.build.threads = 1, o.build.far_field_pass = far_field;
    EXPECT_NO_THROW(voronoi_of_sites({{32, 0}}, fan, o)) << "far field " << far_field;
  }
}

// The same with the general L1 tie-break between points and axis-parallel edges.
TEST(Builder, LShapeAndBoxWithoutAxisTies) {
  const std::vector<Polygon> p{
      Polygon{{{50544, 21177}, {50674, 21177}, {50674, 21918}, {36595, 21918}, {36595, 51870}, {47242, 51870},
               {47242, 20098}, {50544, 20098}}, {}},
      Polygon{{{0, 0}, {21489, 0}, {21489, 10621}, {0, 10621}}, {}}};
  for (const bool far_field : {true, false}) {
    DiagramOptions o;
    o.build.threads = 1, o.build.far_field_pass = far_field, o.build.axis_ties = false;
    EXPECT_NO_THROW(voronoi_of_polygons(p, o)) << "far field " << far_field;
  }
}

// A piece cut out twice (from a cell and a sliver beside it), and a part of it cut out again:
// one piece covering them, whatever their order and direction.
TEST(Builder, JoinKeepsOneOfOverlappingCopies) {
  auto piece = [](double y1, double y2) {
    Piece p;
    p.a = 1, p.b = 2, p.p = {2, y1}, p.q = {2, y2}, p.d1 = y1 - 51197, p.d2 = y2 - 51197;
    return p;
  };
  const std::vector<Piece> raw{piece(51197, 59934.5), piece(51197, 59934.5), piece(59934.5, 69310),
                               piece(69310, 59934.5), piece(60000, 65000), piece(69310, 78685.5)};
  std::vector<std::size_t> order{0, 1, 2, 3, 4, 5};
  do {
    std::vector<Piece> v;
    for (std::size_t i : order) v.push_back(raw[i]);
    join_pair(v);
    ASSERT_EQ(v.size(), 1u);
    EXPECT_EQ(std::min(v[0].p.y, v[0].q.y), 51197);
    EXPECT_EQ(std::max(v[0].p.y, v[0].q.y), 78685.5);
    EXPECT_EQ(v[0].p.x, 2);
    EXPECT_EQ(v[0].d1, v[0].p.y - 51197);
    EXPECT_EQ(v[0].d2, v[0].q.y - 51197);
  } while (std::next_permutation(order.begin(), order.end()));
}

TEST(Builder, JoinKeepsAPieceWhoseEndHasACrumbOfRounding) {
  // A fuzzer finding near 2^24: at a steep edge's corner the subdivision left, beside the
  // corner's separator in two parts, a crumb 3e-8 long running sideways. The union was taken
  // along the crumb, the shorter, and the separator was lost (the check failed). One piece
  // from the corner down, whatever the order.
  const double y0 = 16777218;
  auto piece = [](double x1, double y1, double x2, double y2) {
    Piece p;
    p.p = {x1, y1}, p.q = {x2, y2}, p.a = 30, p.b = 31;
    return p;
  };
  const std::vector<Piece> parts{piece(-245, y0, -245, y0 - 1), piece(-245, y0 - 1, -245, y0 - 1.5),
                                 piece(-245.00000002208981, y0 + 2.2e-8, -244.9999999999709, y0 + 2.2e-8)};
  for (int order = 0; order < 3; ++order) {
    std::vector<Piece> v{parts[order], parts[(order + 1) % 3], parts[(order + 2) % 3]};
    std::sort(v.begin(), v.end(), join_order);
    join_pair(v);
    ASSERT_EQ(v.size(), 1u) << "order " << order;
    EXPECT_NEAR(std::fabs(v[0].p.y - v[0].q.y), 1.5, 1e-7) << "order " << order;
    EXPECT_NEAR(v[0].p.x, -245, 1e-7);
    EXPECT_NEAR(v[0].q.x, -245, 1e-7);
  }
}

// build_pieces joins the tiles' pieces on two threads, split at a pivot owner pair: the same
// pieces in the same order as on one. Pairs of up to 64 pieces, in runs along a line (that join),
// copies and overlaps, in any order: a pair cut at the pivot would stay in two runs.
TEST(Builder, JoinOnTwoThreadsAsOnOne) {
  std::mt19937_64 rng(11);
  std::vector<Piece> raw;
  for (std::int32_t pair = 0; raw.size() < 200000; ++pair) {
    const std::int32_t a = pair / 7, b = a + 1 + pair % 7;
    const double y = double(rng() % 1000), step = 1 + double(rng() % 4);
    const int n = 1 + int(rng() % 64);
    for (int k = 0; k < n; ++k) {
      Piece p;
      p.a = a, p.b = b;
      const double x = double(rng() % 80) * step;
      p.p = {x, y + (rng() % 16 == 0 ? 1 : 0)};
      p.q = {x + step * double(1 + rng() % 3), y};
      p.d1 = 0.5 * p.p.x + p.p.y, p.d2 = 0.5 * p.q.x + p.q.y;  // a clearance is a function of the place
      raw.push_back(p);
    }
  }
  std::shuffle(raw.begin(), raw.end(), rng);
  std::vector<Piece> one = raw, two = raw;
  detail::join_pieces(one, 1);
  detail::join_pieces(two, 2);
  ASSERT_LT(one.size(), raw.size() / 2);  // most pieces joined
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t i = 0; i < one.size(); ++i) {
    ASSERT_EQ(one[i].a, two[i].a) << i;
    ASSERT_EQ(one[i].b, two[i].b) << i;
    ASSERT_EQ(one[i].p.x, two[i].p.x) << i;
    ASSERT_EQ(one[i].p.y, two[i].p.y) << i;
    ASSERT_EQ(one[i].q.x, two[i].q.x) << i;
    ASSERT_EQ(one[i].q.y, two[i].q.y) << i;
    ASSERT_EQ(one[i].d1, two[i].d1) << i;
    ASSERT_EQ(one[i].d2, two[i].d2) << i;
  }
}
