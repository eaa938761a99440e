// Stretches (chains of pieces between the same two owners) taken from a diagram.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "linf/diagram/diagram.hpp"
#include "linf/gauges/gauge.hpp"
#include "linf/geometry/sites.hpp"
#include "linf/gauges/stretch.hpp"
#include "gauges/chain.hpp"
#include "layouts.hpp"
#include "same_stretches.hpp"

using namespace linf;
using linf::testing::expect_same;

namespace {

// Rows of 50 wide tracks at a 100 pitch, random lengths and gaps: a routed-metal-like block.
std::vector<Polygon> tracks(std::uint64_t seed, Coord rows, Coord length) {
  std::vector<Polygon> out;
  std::mt19937_64 rng(seed);
  for (Coord row = 0; row < rows; ++row)
    for (Coord x = Coord(rng() % 300); x < length;) {
      const Coord w = 150 + Coord(rng() % 1350);
      out.push_back(linf::testing::box(x, row * 100, x + w, row * 100 + 50));
      x += w + 50 + Coord(rng() % 550);
    }
  return out;
}

}  // namespace

// The flow builds the gauges' stretches by consuming the pieces (take_stretches, memory given
// back as it goes); it must give the stretches of the const version, in the same order, with
// and without the measurable-pair filter, on every style of layout.
TEST(Stretches, TakingThePiecesGivesTheSameStretches) {
  using linf::testing::Style;
  std::size_t compared = 0;
  for (Style style : {Style::Rectilinear, Style::Octilinear, Style::AnyAngle})
    for (std::uint64_t seed = 1; seed <= 40; ++seed) {
      Result r = voronoi_of_polygons(linf::testing::random_layout(seed, style, 8));
      const Stretches all = stretches_of(r.diagram);
      const Stretches measurable = gauge_stretches(r.diagram);
      Diagram copy = r.diagram;
      const Stretches taken_all = take_stretches(copy);
      EXPECT_TRUE(copy.pieces.empty());
      const Stretches taken = take_gauge_stretches(r.diagram);
      EXPECT_TRUE(r.diagram.pieces.empty());
      expect_same(all, taken_all);
      expect_same(measurable, taken);
      compared += all.size() + measurable.size();
      EXPECT_LT(measurable.size(), all.size());
    }
  EXPECT_GT(compared, 1000u);
}

// Large enough that the consumed pieces' pages are given back several times on the way.
TEST(Stretches, TakingManyPiecesGivesTheSameStretches) {
  Result r = voronoi_of_polygons(tracks(11, 100, 60000));
  ASSERT_GT(r.diagram.pieces.size(), std::size_t(2) << 16);  // released at least twice
  const Stretches want = gauge_stretches(r.diagram);
  const Stretches got = take_gauge_stretches(r.diagram);
  expect_same(want, got);
}

// A diagram whose pieces are not grouped by owner pair (not the builder's order) is taken the
// general way, with the same result.
TEST(Stretches, TakingShuffledPiecesGivesTheSameStretches) {
  Result r = voronoi_of_polygons(linf::testing::random_layout(3, linf::testing::Style::Rectilinear, 8));
  Diagram shuffled = r.diagram;
  std::reverse(shuffled.pieces.begin(), shuffled.pieces.end());
  const Stretches want = stretches_of(shuffled);
  const Stretches got = take_stretches(shuffled);
  expect_same(want, got);
  EXPECT_TRUE(shuffled.pieces.empty());
}

// The gauges let go of the stretches that make no gauge; what is kept is the same stretches, in
// the same order, large enough that pages are given back; and every gauge still lies on its own.
TEST(Stretches, KeepingSomeKeepsThemWhole) {
  const Diagram d = voronoi_of_polygons(tracks(5, 60, 40000)).diagram;
  const Stretches all = gauge_stretches(d);
  ASSERT_GT(all.size(), 10000u);  // a third dropped is tens of pages of each array
  std::vector<bool> keep(all.size());
  for (std::size_t i = 0; i < keep.size(); ++i) keep[i] = (i * 7919) % 3 != 0;
  Stretches kept = gauge_stretches(d);
  kept.keep_only(keep);
  std::size_t k = 0;
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (!keep[i]) continue;
    ASSERT_LT(k, kept.size());
    expect_same(all[i], kept[k++]);
    if (HasFatalFailure()) return;
  }
  EXPECT_EQ(k, kept.size());

  const Gauges g = gauges_of(d);
  EXPECT_EQ(g.measurable, all.size());
  EXPECT_LT(g.stretches.size(), all.size());
  for (std::size_t i = 0; i < g.gauges.size(); ++i) {
    const Gauge& x = g.gauges[i];
    const Stretch s = g.stretches[x.stretch];
    ASSERT_TRUE((s.a == x.a && s.b == x.b) || x.type != GaugeType::Internal) << "gauge " << i + 1;
    if (x.neighbour >= 0) ASSERT_EQ(g.stretches[x.neighbour].kind, PieceKind::External);
  }
}

// A pair's pieces are walked into paths by flat arrays when they are few (chain_few) and by a
// map and a set otherwise (chain_any): the same paths, to the last bit, on random graphs of up
// to kFewPieces pieces between grid points: branches (vertices of degree 3 and 4, where the
// odd-degree start decides), cycles, repeated pieces and pieces of no length.
TEST(Stretches, FewPiecesAreWalkedAsMany) {
  const Sites sites = sites_of_polygons({linf::testing::box(0, 0, 40, 10), linf::testing::box(0, 30, 40, 40)});
  std::mt19937_64 rng(7);
  std::size_t branched = 0;
  for (int round = 0; round < 2000; ++round) {
    const std::size_t n = 1 + rng() % detail::kFewPieces;
    const int grid = 2 + int(rng() % 4);  // few grid points: vertices where many pieces meet
    std::vector<Piece> pieces(n);
    for (Piece& p : pieces) {
      p.p = {double(rng() % grid) * 10, 12 + double(rng() % grid) * 4};
      p.q = rng() % 8 == 0 ? p.p : Vec2{double(rng() % grid) * 10, 12 + double(rng() % grid) * 4};
      p.d1 = 1 + double(rng() % 16), p.d2 = 1 + double(rng() % 16);
      p.a = 1, p.b = 9;
      p.kind = PieceKind(rng() % 2);
    }
    std::vector<std::int32_t> ids;
    for (std::size_t i = 0; i < n; ++i)
      if (i == 0 || rng() % 4 != 0) ids.push_back(std::int32_t(i));
    Stretches few, any;
    detail::chain_few(sites, pieces.data(), ids.data(), ids.size(), few);
    detail::chain_any(sites, pieces.data(), ids.data(), ids.size(), any);
    expect_same(any, few);
    if (::testing::Test::HasFatalFailure()) return;
    branched += any.size() > 1;
  }
  EXPECT_GT(branched, 1000u);  // most graphs need several paths: the start rule is exercised
}
