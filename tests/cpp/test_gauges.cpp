// Gauges on drawn configurations, one per rule of the README's "Gauges" section.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "linf/diagram.hpp"
#include "linf/gauge.hpp"
#include "layouts.hpp"

using namespace linf;
using linf::testing::box;

namespace {

// A gauge as the outputs report it: with its measurement line and normalised score.
struct Reported : Gauge {
  Vec2 p, q;
  double norm_score = 0;
};

std::vector<Reported> gauges(const std::vector<Polygon>& polys) {
  const Result r = voronoi_of_polygons(polys);
  const Gauges g = gauges_of(r.diagram);
  std::vector<Reported> out;
  for (const Gauge& x : g.gauges) {
    Reported y{x};
    const MeasurementLine m = measurement_line(r.diagram.sites, x);
    y.p = m.p, y.q = m.q;
    y.norm_score = g.norm_score(x);
    out.push_back(y);
  }
  return out;
}

template <class All>
auto of_type(const All& all, GaugeType t) {
  std::vector<typename All::value_type> out;
  using G = typename All::value_type;
  for (const G& g : all)
    if (g.type == t) out.push_back(g);
  return out;
}

double line_length(const Reported& g) { return std::hypot(g.q.x - g.p.x, g.q.y - g.p.y); }

// The same stretches in the same order, to the last bit.
void expect_same(const Stretch& a, const Stretch& b) {
  ASSERT_EQ(a.a, b.a);
  ASSERT_EQ(a.b, b.b);
  ASSERT_EQ(a.kind, b.kind);
  ASSERT_EQ(a.length, b.length);
  ASSERT_EQ(a.path.size(), b.path.size());
  for (std::size_t k = 0; k < a.path.size(); ++k) {
    ASSERT_EQ(a.path[k].x, b.path[k].x);
    ASSERT_EQ(a.path[k].y, b.path[k].y);
    ASSERT_EQ(a.clearance[k], b.clearance[k]);
  }
}

void expect_same(const Stretches& want, const Stretches& got) {
  ASSERT_EQ(want.size(), got.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    expect_same(want[i], got[i]);
    if (::testing::Test::HasFatalFailure()) return;
  }
}

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

TEST(Gauges, BarHasOneWidthAtItsCentre) {
  const auto all = gauges({box(0, 0, 1000, 40)});
  const auto in = of_type(all, GaugeType::Internal);
  ASSERT_EQ(in.size(), 1u);
  EXPECT_NEAR(in[0].cd, 40, 1e-9);
  EXPECT_NEAR(in[0].score, 40, 1e-9);
  EXPECT_NEAR(in[0].at.x, 500, 1e-6);
  EXPECT_NEAR(in[0].at.y, 20, 1e-6);
  EXPECT_NEAR(line_length(in[0]), 40, 1e-9);  // across the bar, ends on its two long edges
  EXPECT_NEAR(in[0].tiebreak, 960, 1e-6);     // extension: the constant-width medial axis
  EXPECT_TRUE(of_type(all, GaugeType::External).empty());
}

TEST(Gauges, SquareViaIsMeasuredBothWays) {
  const auto in = of_type(gauges({box(0, 0, 30, 30)}), GaugeType::Internal);
  ASSERT_EQ(in.size(), 2u);
  for (const Gauge& g : in) {
    EXPECT_NEAR(g.cd, 30, 1e-9);
    EXPECT_NEAR(g.at.x, 15, 1e-6);
    EXPECT_NEAR(g.at.y, 15, 1e-6);
  }
  EXPECT_NE(std::fabs(in[0].q.x - in[0].p.x) > 1, std::fabs(in[1].q.x - in[1].p.x) > 1);
}

TEST(Gauges, OneGapOneGauge) {
  // Two bars side by side, offset: the gap continues past the corners at the same clearance,
  // owned by the corner vertices; only the edge-to-edge gauge is reported.
  const auto ex = of_type(gauges({box(0, 0, 1000, 40), box(300, 70, 1300, 110)}), GaugeType::External);
  const auto narrow = std::count_if(ex.begin(), ex.end(), [](const Gauge& g) { return g.cd < 31; });
  EXPECT_EQ(narrow, 1);
  auto it = std::min_element(ex.begin(), ex.end(), [](auto& a, auto& b) { return a.cd < b.cd; });
  EXPECT_NEAR(it->cd, 30, 1e-9);
  EXPECT_NEAR(it->at.x, 650, 1e-6);  // the centre of the overlap
}

TEST(Gauges, KissingCornersOnADiagonal) {
  // Corners exactly on a 45-degree diagonal: the L-inf bisector dips to half the offset in the
  // middle of a piece whose ends are farther; the gauge finds the dip.
  const auto ex = of_type(gauges({box(0, 0, 100, 100), box(190, 190, 300, 300)}), GaugeType::External);
  ASSERT_FALSE(ex.empty());
  EXPECT_NEAR(ex.front().cd, 90, 1e-6);
  EXPECT_NEAR(ex.front().at.x, 145, 1e-6);
  EXPECT_NEAR(ex.front().at.y, 145, 1e-6);
}

TEST(Gauges, JogIsMeasuredAcrossItsReflexCorners) {
  Polygon jog{{{0, 0}, {80, 0}, {80, 400}, {120, 400}, {120, 900}, {40, 900}, {40, 480}, {0, 480}}, {}};
  const auto in = of_type(gauges({jog}), GaugeType::Internal);
  auto diag = std::find_if(in.begin(), in.end(), [](const Gauge& g) { return g.at.y > 400 && g.at.y < 480; });
  ASSERT_NE(diag, in.end());
  EXPECT_NEAR(diag->cd, 80, 1e-9);
}

TEST(Gauges, SandwichBetweenTwoNeighbours) {
  // Spaces 60 and 50 around a 50 wide line: d = 60/2 + 50 + 50/2 = 105, score 52.5.
  const auto all = gauges({box(0, 0, 1000, 40), box(0, 100, 1000, 150), box(0, 200, 1000, 240)});
  const auto s = of_type(all, GaugeType::Sandwich);
  ASSERT_EQ(s.size(), 1u);
  EXPECT_NEAR(s[0].score, 52.5, 1e-9);
  EXPECT_NEAR(s[0].cd, 50, 1e-9);
  EXPECT_NEAR(s[0].at.y, 125, 1e-6);
  EXPECT_NEAR(s[0].tiebreak, 950, 1e-6);  // overlap of the three stretches
}

TEST(Gauges, CombNeedsTwoTeethTNeedsOne) {
  // Base 50 wide; teeth 40 wide at gaps 30 and 40 (comb), one tooth at gap 40 (T).
  const auto all = gauges({box(0, 0, 1000, 50), box(100, 80, 140, 300), box(500, 90, 540, 300),
                           box(2000, 0, 3000, 50), box(2400, 90, 2440, 300)});
  const auto comb = of_type(all, GaugeType::Comb);
  const auto t = of_type(all, GaugeType::T);
  ASSERT_EQ(comb.size(), 1u);
  EXPECT_EQ(comb[0].teeth, 2);
  EXPECT_NEAR(comb[0].score, 0.75 * (15 + 25), 1e-9);  // the nearer tooth: d_tb = 30/2 + 50/2
  EXPECT_NEAR(comb[0].at.x, 120, 1e-6);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_NEAR(t[0].score, 0.80 * (20 + 25), 1e-9);
  EXPECT_NEAR(t[0].tiebreak, 40, 1e-6);  // overlap = the tooth's width
  // Two long parallel lines are neighbours, not teeth.
  EXPECT_TRUE(of_type(gauges({box(0, 0, 1000, 50), box(0, 90, 1000, 140)}), GaugeType::T).empty());
}

TEST(Gauges, RankedByScoreThenContextThenTiebreak) {
  const auto all = gauges({box(0, 0, 1000, 40), box(0, 100, 1000, 150), box(0, 200, 1000, 240),
                           box(2000, 0, 3000, 50), box(2100, 80, 2140, 300), box(2500, 90, 2540, 300),
                           box(6000, 0, 6030, 30)});
  auto context = [](GaugeType t) {
    switch (t) {
      case GaugeType::Sandwich: return 0;
      case GaugeType::Comb: return 1;
      case GaugeType::T: return 2;
      case GaugeType::External: return 3;
      default: return 4;
    }
  };
  double top = 0;
  for (const Gauge& g : all) top = std::max(top, g.score);
  for (std::size_t i = 0; i < all.size(); ++i) {
    EXPECT_NEAR(all[i].norm_score, all[i].score / top, 1e-12);
    if (i == 0) continue;
    const Gauge& a = all[i - 1];
    const Gauge& b = all[i];
    ASSERT_LE(a.score, b.score + 1e-6);
    if (std::fabs(a.score - b.score) < 1e-6) {
      ASSERT_LE(context(a.type), context(b.type));
      if (a.type == b.type) ASSERT_GE(a.tiebreak, b.tiebreak - 1e-6);
    }
  }
  // The comb (score 30) outranks the 30 wide via and the 30 space at the same score.
  EXPECT_EQ(all[0].type, GaugeType::Comb);
}

TEST(Gauges, NotchInsideOneShapeIsAnExternalGauge) {
  Polygon u{{{0, 0}, {100, 0}, {100, 100}, {70, 100}, {70, 20}, {30, 20}, {30, 100}, {0, 100}}, {}};
  const auto ex = of_type(gauges({u}), GaugeType::External);
  auto it = std::find_if(ex.begin(), ex.end(), [](const Gauge& g) { return std::fabs(g.cd - 40) < 1e-9; });
  ASSERT_NE(it, ex.end());
  EXPECT_NEAR(it->at.x, 50, 1e-6);
}

TEST(Gauges, SpacesBeyondTenWidthsAreNotPattern) {
  // Two 40 wide bars 500 apart (12.5 widths): the far field, no external gauge; 300 apart: one.
  const Diagram far = voronoi_of_polygons({box(0, 0, 1000, 40), box(0, 540, 1000, 580)}).diagram;
  const Gauges g = gauges_of(far);
  EXPECT_NEAR(g.typical_width, 40, 1e-9);
  EXPECT_NEAR(g.space_limit, 400, 1e-9);
  EXPECT_TRUE(of_type(g.gauges, GaugeType::External).empty());
  GaugeOptions all;
  all.space_limit_widths = 0;
  EXPECT_FALSE(of_type(gauges_of(far, all).gauges, GaugeType::External).empty());
  EXPECT_FALSE(of_type(gauges({box(0, 0, 1000, 40), box(0, 340, 1000, 380)}), GaugeType::External).empty());
}

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
