// The diagram of drawn configurations: pieces' kinds, tie rules, the clip box.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "linf/diagram/classify.hpp"
#include "linf/diagram/diagram.hpp"
#include "layouts.hpp"

using namespace linf;
using linf::testing::box;

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

TEST(Diagram, SmallFeaturesFarFromTheOrigin) {
  // The diagram moves with its input: small features pass the check anywhere inside +-2^30.
  // Each layout once where it failed (pieces a few DBU apart joined as if they met, cells of a
  // fraction of a DBU lost to the rounding of their area, the checker taking a site nearer by
  // 1e-5 DBU for a tie) and once against the limit.
  using linf::testing::random_layout;
  using linf::testing::Style;
  struct Case { std::vector<Polygon> layout; Coord dx, dy; };
  const Coord limit = (Coord(1) << 30) - 1000;
  const std::vector<Polygon> boxes{box(0, 0, 100, 40), box(150, 0, 200, 300)};
  const std::vector<Polygon> rect8 = random_layout(8, Style::Rectilinear, 14);
  const std::vector<Polygon> rect26 = random_layout(26, Style::Rectilinear, 12);
  const std::vector<Polygon> any20 = random_layout(20, Style::AnyAngle, 6);
  const Case cases[] = {{boxes, 21562499, 21562499},
                        {boxes, limit, -limit},
                        {rect8, (Coord(1) << 26) - 500, 500 - (Coord(1) << 26)},
                        {rect8, -limit, limit},
                        {rect26, (Coord(1) << 24) - 500, 500 - (Coord(1) << 24)},
                        {rect26, limit, limit},
                        {any20, (Coord(1) << 28) - 500, 500 - (Coord(1) << 28)},
                        {any20, -limit, -limit}};
  DiagramOptions opt;
  opt.build.threads = 1;
  for (const Case& c : cases) {
    std::vector<Polygon> moved = c.layout;
    for (Polygon& p : moved) {
      for (Point& q : p.outer) q.x += c.dx, q.y += c.dy;
      for (Ring& h : p.holes)
        for (Point& q : h) q.x += c.dx, q.y += c.dy;
    }
    EXPECT_NO_THROW(voronoi_of_polygons(moved, opt)) << "moved by " << c.dx << ", " << c.dy;
  }
}

TEST(Diagram, ShallowSegmentMovesWithItsInput) {
  // A segment of slope 1/34304 beside its endpoint's region: its near-ties are 1e-4 DBU wide,
  // which the builder resolves only in coordinates relative to the layout (found by the
  // fuzzer against the +-2^30 limit, where pieces went missing). The same pieces anywhere,
  // but for pieces of no length (at the origin a vertex on the clip box is one; far away the
  // join takes it in).
  const std::vector<Segment> local{{{34304, 1}, {0, 0}}, {{245, 12}, {1013, 20}}, {{390, 0}, {0, 0}}};
  DiagramOptions opt;
  opt.build.threads = 1;
  auto with_length = [](const Result& r) {
    std::vector<Piece> out;
    for (const Piece& p : r.diagram.pieces)
      if (std::max(std::fabs(p.q.x - p.p.x), std::fabs(p.q.y - p.p.y)) > 1e-6) out.push_back(p);
    return out;
  };
  const std::vector<Piece> at_origin = with_length(voronoi_of_sites({}, local, opt));
  ASSERT_GT(at_origin.size(), 12u);
  const Coord offsets[][2] = {{1073707519, 1073741785}, {-1073707519, 1073741785}, {1073707519, 0}};
  for (const auto& o : offsets) {
    std::vector<Segment> moved = local;
    for (Segment& s : moved) s.a.x += o[0], s.a.y += o[1], s.b.x += o[0], s.b.y += o[1];
    std::vector<Piece> there;
    ASSERT_NO_THROW(there = with_length(voronoi_of_sites({}, moved, opt))) << "moved by " << o[0] << ", " << o[1];
    ASSERT_EQ(there.size(), at_origin.size());
    for (std::size_t i = 0; i < there.size(); ++i) {
      const Piece &p = there[i], &q = at_origin[i];
      EXPECT_EQ(p.a, q.a);
      EXPECT_EQ(p.b, q.b);
      EXPECT_NEAR(p.p.x - double(o[0]), q.p.x, 1e-6);
      EXPECT_NEAR(p.p.y - double(o[1]), q.p.y, 1e-6);
      EXPECT_NEAR(p.q.x - double(o[0]), q.q.x, 1e-6);
      EXPECT_NEAR(p.q.y - double(o[1]), q.q.y, 1e-6);
    }
  }
}
