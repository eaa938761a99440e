// Thousands of seeded random small layouts, every one checked by the independent checker and
// by the piece-end oracle (tests/fuzz/ends_check.hpp: no piece ends while its edge goes on).
#include <gtest/gtest.h>

#include <chrono>

#include "../fuzz/ends_check.hpp"
#include "layouts.hpp"
#include "linf/diagram/diagram.hpp"

using namespace linf;
using linf::testing::Style;

namespace {
void run_style(Style style, int count, int shapes) {
  int failures = 0;
  std::size_t pieces = 0, points = 0, separated = 0, judged = 0;
  const auto t0 = std::chrono::steady_clock::now();
  DiagramOptions opt;
  opt.checker.crossing_pairs = 300;
  for (int seed = 1; seed <= count; ++seed) {
    try {
      Result r = voronoi_of_polygons(linf::testing::random_layout(std::uint64_t(seed), style, shapes), opt);
      pieces += r.diagram.pieces.size();
      points += r.check.sampled_points;
      separated += r.check.pairs_separated;
      const linf::fuzz::EndsReport e = linf::fuzz::check_piece_ends(r.diagram);
      judged += e.judged;
      if (!e.failure.empty() && ++failures <= 5) ADD_FAILURE() << "seed " << seed << ": " << e.failure;
    } catch (const DiagramError& e) {
      if (++failures <= 5) ADD_FAILURE() << "seed " << seed << ": " << e.what();
    }
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("[random] style %d: %d layouts, %zu pieces, %zu points sampled, %zu separated pairs, %zu piece ends "
              "judged, %.2f s\n", int(style), count, pieces, points, separated, judged, s);
  EXPECT_EQ(failures, 0);
  EXPECT_GT(separated, std::size_t(count));  // the completeness test really ran
  EXPECT_GT(judged, std::size_t(count));     // and the piece-end oracle
}
}  // namespace

TEST(RandomLayouts, Rectilinear) { run_style(Style::Rectilinear, 1000, 6); }
TEST(RandomLayouts, Octilinear) { run_style(Style::Octilinear, 1000, 6); }
TEST(RandomLayouts, AnyAngle) { run_style(Style::AnyAngle, 1000, 5); }

// The piece-end oracle itself: it must catch a piece cut short (a mutation of a diagram that
// passes), and must not report the thin wedge the fuzzer found (seed 35321862): segment 2-15's
// edge ends where segment 14's region starts, a wedge 1.5 degrees wide between two edges.
namespace {
Result wedge_layout() {
  const Coord o = 1073679055;  // the finding's coordinates, near +2^30
  auto P = [&](Coord x, Coord y) { return Point{o + x, o + y}; };
  const std::vector<Segment> segments = {
      {P(917, 512), P(18, 34304)},  {P(7946, 7710), P(7728, 62750)}, {P(7710, 7710), P(7728, 7710)},
      {P(7728, 7680), P(62768, 5155)}, {P(34322, 1), P(22, 0)}};
  return voronoi_of_sites({P(18, 0)}, segments);
}
}  // namespace

TEST(PieceEndOracle, ThinWedgeOfAThirdSiteIsNoFinding) {
  const Result r = wedge_layout();
  const linf::fuzz::EndsReport e = linf::fuzz::check_piece_ends(r.diagram);
  EXPECT_TRUE(e.failure.empty()) << e.failure;
  EXPECT_GT(e.judged, 0u);
}

TEST(PieceEndOracle, CatchesAPieceCutShort) {
  Result r = voronoi_of_polygons({{{{0, 0}, {1000, 0}, {1000, 100}, {0, 100}}, {}},
                                  {{{0, 300}, {1000, 300}, {1000, 400}, {0, 400}}, {}}});
  ASSERT_TRUE(linf::fuzz::check_piece_ends(r.diagram).failure.empty());
  // The piece midway between the boxes' facing long edges (y = 200, x from 0 to 1000), cut
  // to half its length: just beyond the cut, the two edges are still the nearest by 100 DBU.
  std::size_t middle = r.diagram.pieces.size();
  for (std::size_t i = 0; i < r.diagram.pieces.size(); ++i) {
    const Piece& p = r.diagram.pieces[i];
    if (p.p.y == 200 && p.q.y == 200 && std::min(p.p.x, p.q.x) == 0 && std::max(p.p.x, p.q.x) == 1000) middle = i;
  }
  ASSERT_LT(middle, r.diagram.pieces.size());
  Piece& p = r.diagram.pieces[middle];
  p.q = {(p.p.x + p.q.x) / 2, (p.p.y + p.q.y) / 2};
  p.d2 = (p.d1 + p.d2) / 2;
  EXPECT_NE(linf::fuzz::check_piece_ends(r.diagram).failure, "");
}
