// The small inputs on which CGAL 5.5.1's L-inf segment Delaunay graph fails (foundation issue).
// Our diagram must pass the checker on all of them, and the checker must reject CGAL's case 3.
#include <gtest/gtest.h>

#include "linf/diagram/diagram.hpp"
#include "linf/baseline/cgal_baseline.hpp"
#include "linf/geometry/sites.hpp"

using namespace linf;

namespace {
std::vector<Segment> segs(std::initializer_list<std::array<Coord, 4>> l) {
  std::vector<Segment> s;
  for (auto& g : l) s.push_back({{g[0], g[1]}, {g[2], g[3]}});
  return s;
}
std::vector<Polygon> case3() {
  return {{{{810, 924}, {1147, 924}, {1147, 964}, {810, 964}}, {}},
          {{{1210, 810}, {1210, 903}, {1317, 1010}, {1517, 1010}, {1517, 917}, {1410, 810}}, {}}};
}
void expect_checked(const Result& r) {
  EXPECT_TRUE(r.check.ok()) << (r.check.messages.empty() ? "" : r.check.messages.front());
  EXPECT_GT(r.check.sampled_points, 0u);
  EXPECT_GT(r.diagram.pieces.size(), 0u);
}
}  // namespace

TEST(Reproducers, Case1ThreeSegments) {
  expect_checked(voronoi_of_sites({}, segs({{210, 52, 585, 52}, {245, 12, 245, 20}, {390, 0, 0, 0}})));
}

TEST(Reproducers, Case2FourSegmentsSegfaultInCgal) {
  expect_checked(voronoi_of_sites(
      {}, segs({{10025, 280, 10400, 280}, {10060, 240, 10060, 248}, {10205, 228, 9815, 228}, {8115, 280, 8115, 288}})));
}

TEST(Reproducers, Case3BoxAndFortyFiveDegreeEdge) {
  Result r = voronoi_of_polygons(case3());
  expect_checked(r);
  // The piece CGAL draws wrongly: between vertex (1147,964) and the 45-degree edge. Ours must
  // exist and every point of it must be equidistant (the checker), and it must be external.
  bool found = false;
  for (const Piece& p : r.diagram.pieces) {
    const Site& a = r.diagram.sites.sites[p.a];
    const Site& b = r.diagram.sites.sites[p.b];
    auto is_v = [](const Site& s) { return s.is_point() && s.a == Point{1147, 964}; };
    auto is_e = [](const Site& s) {
      return !s.is_point() && ((s.a == Point{1210, 903} && s.b == Point{1317, 1010}) ||
                               (s.b == Point{1210, 903} && s.a == Point{1317, 1010}));
    };
    if ((is_v(a) && is_e(b)) || (is_v(b) && is_e(a))) {
      found = true;
      EXPECT_EQ(p.kind, PieceKind::External);
    }
  }
  EXPECT_TRUE(found);
}

TEST(Reproducers, CheckerRejectsCgalCase3) {
  Sites s = sites_of_polygons(merge_polygons(case3()));
  Diagram d;
  d.sites = s;
  d.clip = clip_box(s);
  d.pieces = cgal_linf_pieces(s, d.clip, 0);
  ASSERT_GT(d.pieces.size(), 0u);
  CheckReport rep = check_diagram(d);
  EXPECT_FALSE(rep.ok());
  EXPECT_GT(rep.worst_error, 5.0);  // CGAL's edge is off by about 10 DBU
}

TEST(Reproducers, CheckerRejectsAMissingPiece) {
  Result r = voronoi_of_polygons(case3());
  Diagram d = r.diagram;
  // Remove every external piece: the pairs test must notice.
  std::vector<Piece> kept;
  for (const Piece& p : d.pieces)
    if (p.kind != PieceKind::External) kept.push_back(p);
  ASSERT_LT(kept.size(), d.pieces.size());
  d.pieces = kept;
  CheckOptions o;
  o.crossing_pairs = 20000;
  CheckReport rep = check_diagram(d, o);
  EXPECT_GT(rep.missing_edge_errors, 0u);
}

TEST(Reproducers, CheckerRejectsAShiftedPiece) {
  Result r = voronoi_of_polygons(case3());
  Diagram d = r.diagram;
  d.pieces[0].p.x += 3, d.pieces[0].q.x += 3;
  EXPECT_FALSE(check_diagram(d).ok());
}

// A piece equidistant from its two owners at the stated clearances, but with a third site
// closer: the points A (0,0) and B (10,0), their bisector x = 5 claimed from y = -20 to 20
// straight through C (5,2). Only the closer-site test can see it.
TEST(Reproducers, CheckerRejectsAPiecePastACloserSite) {
  Diagram d;
  d.sites = sites_of_plain({{0, 0}, {10, 0}, {5, 2}}, {});
  d.clip = clip_box(d.sites);
  Piece p;
  p.p = {5, -20}, p.q = {5, 20};
  p.d1 = p.d2 = 20;
  for (std::size_t i = 0; i < d.sites.sites.size(); ++i) {
    const Site& s = d.sites.sites[i];
    if (s.a.x == 0 && s.a.y == 0) p.a = std::int32_t(i);
    if (s.a.x == 10 && s.a.y == 0) p.b = std::int32_t(i);
  }
  d.pieces = {p};
  CheckOptions o;
  o.samples_per_piece = 5;
  const CheckReport rep = check_diagram(d, o);
  EXPECT_EQ(rep.equidistance_errors, 0u);
  EXPECT_EQ(rep.clearance_errors, 0u);
  // Samples at y = -20, -10, 0, 10, 20: C is at 22, 12, 2, 8, 18 against the owners' 20, 10,
  // 5, 10, 20, so closer at the last three.
  EXPECT_EQ(rep.closer_site_errors, 3u);
  EXPECT_FALSE(rep.ok());
}

// A piece on a line where a third site ties with its two owners, labelled with the third: the
// sweep's fault at a point of no width with two rays (three segments at (0, 0) with one
// separator, the diagonal x + y = 0: A to (-3, -3), B to (3, 3) in line with it, C to (3, 2)).
// The ray above is A and B's edge; labelled A and C it is equidistant from its owners with no
// site closer, so only the owners of the pairs it separates show it.
TEST(Reproducers, CheckerRejectsAPieceLabelledWithATiedThirdSite) {
  const Result r = voronoi_of_sites({}, {{{0, 0}, {-3, -3}}, {{0, 0}, {3, 3}}, {{0, 0}, {3, 2}}});
  ASSERT_TRUE(r.check.ok());
  const SiteList& S = r.diagram.sites.sites;
  auto segment_to = [&](Point far) {
    for (std::size_t i = 0; i < S.size(); ++i)
      if (!S[i].is_point() && (S[i].a == far || S[i].b == far)) return std::int32_t(i);
    return std::int32_t(-1);
  };
  const std::int32_t A = segment_to({-3, -3}), B = segment_to({3, 3}), C = segment_to({3, 2});
  Diagram d = r.diagram;
  int relabelled = 0;
  for (Piece& p : d.pieces)
    if (std::minmax(p.a, p.b) == std::minmax(A, B)) p.a = std::min(A, C), p.b = std::max(A, C), ++relabelled;
  ASSERT_EQ(relabelled, 1);
  const CheckReport rep = check_diagram(d);
  EXPECT_EQ(rep.equidistance_errors + rep.clearance_errors + rep.closer_site_errors + rep.missing_edge_errors, 0u);
  EXPECT_GT(rep.wrong_owner_errors, 0u);
  EXPECT_FALSE(rep.ok());
}
