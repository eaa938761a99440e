// Gauges on drawn configurations, one per rule of docs/design.md, "Gauge rules".
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "linf/diagram/diagram.hpp"
#include "linf/gauges/gauge.hpp"
#include "linf/geometry/distance.hpp"
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

// Horizontal or vertical, exactly: the outputs compare the two ends' coordinates as written.
bool axis_parallel(const Reported& g) { return g.p.x == g.q.x || g.p.y == g.q.y; }

// A line measures along an axis, cd long (unless told), and stays within the gauge point's
// L-inf square.
void expect_across_axis(const Reported& g, double length = -1) {
  if (length < 0) length = g.cd;
  EXPECT_TRUE(axis_parallel(g)) << gauge_type_name(g.type) << " at (" << g.at.x << ", " << g.at.y << "): ("
                                << g.p.x << ", " << g.p.y << ") to (" << g.q.x << ", " << g.q.y << ")";
  EXPECT_NEAR(std::max(std::fabs(g.q.x - g.p.x), std::fabs(g.q.y - g.p.y)), length, 1e-9)
      << gauge_type_name(g.type) << " at (" << g.at.x << ", " << g.at.y << ")";
  for (const Vec2& e : {g.p, g.q})
    EXPECT_LE(std::max(std::fabs(e.x - g.at.x), std::fabs(e.y - g.at.y)), 0.5 * g.cd + 1e-9);
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

TEST(Gauges, LinesOnAxisParallelFeaturesRunAlongAnAxisCdLong) {
  // A bar's width is measured across it, through the gauge point.
  const auto flat = of_type(gauges({box(0, 0, 1000, 40)}), GaugeType::Internal);
  ASSERT_EQ(flat.size(), 1u);
  EXPECT_EQ(flat[0].p.x, 500);
  EXPECT_EQ(flat[0].q.x, 500);
  const auto tall = of_type(gauges({box(0, 0, 40, 1000)}), GaugeType::Internal);
  ASSERT_EQ(tall.size(), 1u);
  EXPECT_EQ(tall[0].p.y, 500);
  EXPECT_EQ(tall[0].q.y, 500);
  // The jog's reflex corners face diagonally, 40 apart in x, 80 in y: measured along y, between
  // the corners' heights, through the gauge point.
  Polygon jog{{{0, 0}, {80, 0}, {80, 400}, {120, 400}, {120, 900}, {40, 900}, {40, 480}, {0, 480}}, {}};
  const auto in = of_type(gauges({jog}), GaugeType::Internal);
  auto neck = std::find_if(in.begin(), in.end(), [](const Gauge& g) { return g.at.y > 400 && g.at.y < 480; });
  ASSERT_NE(neck, in.end());
  EXPECT_EQ(neck->p.x, neck->at.x);
  EXPECT_EQ(std::min(neck->p.y, neck->q.y), 400);
  EXPECT_EQ(std::max(neck->p.y, neck->q.y), 480);
  // An L: its inner corner against the outer edges and the outer corner.
  Polygon ell{{{0, 0}, {100, 0}, {100, 30}, {30, 30}, {30, 100}, {0, 100}}, {}};
  // Corners exactly on a diagonal: either axis; x, the rule's last word, between the corners.
  const auto kiss = of_type(gauges({box(0, 0, 100, 100), box(190, 190, 300, 300)}), GaugeType::External);
  ASSERT_FALSE(kiss.empty());
  EXPECT_EQ(kiss.front().p.y, kiss.front().q.y);
  EXPECT_EQ(std::fabs(kiss.front().q.x - kiss.front().p.x), 90);
  for (const std::vector<Polygon>& layout :
       {std::vector<Polygon>{box(0, 0, 1000, 40)}, {box(0, 0, 40, 1000)}, {jog}, {ell}, {box(0, 0, 30, 30)},
        {box(0, 0, 100, 100), box(190, 190, 300, 300)}, {box(0, 0, 1000, 40), box(300, 70, 1300, 110)},
        {box(0, 0, 1000, 40), box(0, 100, 1000, 150), box(0, 200, 1000, 240)},
        {box(0, 0, 1000, 50), box(100, 80, 140, 300), box(500, 90, 540, 300), box(2000, 0, 3000, 50),
         box(2400, 90, 2440, 300)}}) {
    const auto all = gauges(layout);
    ASSERT_FALSE(all.empty());
    for (const Reported& g : all) expect_across_axis(g);
  }
  // Sandwich and comb measure the sandwiched line and the base across, as an internal gauge.
  const auto sandwich = of_type(gauges({box(0, 0, 1000, 40), box(0, 100, 1000, 150), box(0, 200, 1000, 240)}),
                                GaugeType::Sandwich);
  ASSERT_EQ(sandwich.size(), 1u);
  EXPECT_EQ(sandwich[0].p.x, sandwich[0].q.x);
  EXPECT_EQ(std::min(sandwich[0].p.y, sandwich[0].q.y), 100);
  const auto comb = of_type(gauges({box(0, 0, 1000, 50), box(100, 80, 140, 300), box(500, 90, 540, 300)}),
                            GaugeType::Comb);
  ASSERT_EQ(comb.size(), 1u);
  EXPECT_EQ(comb[0].p.x, comb[0].q.x);
  EXPECT_EQ(std::fabs(comb[0].q.y - comb[0].p.y), 50);
}

TEST(Gauges, LinesAcrossFortyFiveDegreeEdgesArePerpendicular) {
  // A 45-degree wire 30 wide in L-inf: measured perpendicular to its edges, 30 * sqrt(2) long.
  const auto in = of_type(gauges({{{{0, 0}, {1000, 1000}, {970, 1030}, {-30, 30}}, {}}}), GaugeType::Internal);
  auto wide = std::find_if(in.begin(), in.end(), [](const Gauge& g) { return std::fabs(g.cd - 30) < 1e-9; });
  ASSERT_NE(wide, in.end());
  EXPECT_NEAR((wide->q.x - wide->p.x) + (wide->q.y - wide->p.y), 0, 1e-9);
  EXPECT_NEAR(line_length(*wide), 30 * std::sqrt(2.0), 1e-9);
}

TEST(Gauges, EveryLineOnAManhattanLayoutIsHorizontalOrVertical) {
  std::size_t lines = 0, corners = 0, beside = 0;
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    const auto layout = seed <= 30 ? linf::testing::random_layout(seed, linf::testing::Style::Rectilinear, 10)
                                   : linf::testing::block(seed, linf::testing::Style::Rectilinear, 3, 3);
    const Result r = voronoi_of_polygons(layout);
    const Gauges g = gauges_of(r.diagram);
    for (const Gauge& x : g.gauges) {
      Reported y{x};
      const MeasurementLine m = measurement_line(r.diagram.sites, x);
      y.p = m.p, y.q = m.q;
      const Site& a = r.diagram.sites.sites[x.a];
      const Site& b = r.diagram.sites.sites[x.b];
      // Where the gauge's square touches the owners on two adjacent sides, the line is their
      // own L-inf distance long (attained at an end of one of them), at most cd.
      const double apart = std::min({dist_site(double(a.a.x), double(a.a.y), b), dist_site(double(a.b.x), double(a.b.y), b),
                                     dist_site(double(b.a.x), double(b.a.y), a), dist_site(double(b.b.x), double(b.b.y), a)});
      const double length = std::max(std::fabs(y.q.x - y.p.x), std::fabs(y.q.y - y.p.y));
      if (std::fabs(length - x.cd) > 1e-9) {
        ++beside;
        EXPECT_NEAR(length, apart, 1e-9);
        EXPECT_LT(length, x.cd);
      }
      expect_across_axis(y, std::fabs(length - x.cd) > 1e-9 ? apart : x.cd);
      ++lines;
      corners += a.is_point() && b.is_point();
    }
  }
  EXPECT_GT(lines, 1000u);
  EXPECT_GT(corners, 10u);  // corner-to-corner pairs are among them, the lines a Euclidean rule tilts
  EXPECT_LT(beside, lines / 5);
  std::printf("%zu lines, %zu corner to corner, %zu of owners touched on adjacent sides\n", lines, corners, beside);
}

TEST(Gauges, TheSameGaugesOnEveryNumberOfThreads) {
  // Enough stretches for several blocks of 4,096 (the gauges are placed in blocks on the threads,
  // copied into place there, and ranked in two halves).
  const auto layout = linf::testing::block(7, linf::testing::Style::Rectilinear, 20, 20);
  const Result r = voronoi_of_polygons(layout);
  auto placed = [&](int threads) {
    GaugeOptions o;
    o.threads = threads;
    return gauges_of(r.diagram, o);
  };
  const Gauges one = placed(1);
  ASSERT_GT(one.stretches.size(), 3u * 4096u);
  ASSERT_GT(one.gauges.size(), 1u << 14);  // ranked in two halves side by side on 2 and 3 threads
  for (int threads : {2, 3}) {
    const Gauges g = placed(threads);
    ASSERT_EQ(g.gauges.size(), one.gauges.size()) << threads << " threads";
    for (std::size_t i = 0; i < g.gauges.size(); ++i) {
      const Gauge &x = g.gauges[i], &y = one.gauges[i];
      ASSERT_TRUE(x.type == y.type && x.a == y.a && x.b == y.b && x.at.x == y.at.x && x.at.y == y.at.y &&
                  x.score == y.score && x.cd == y.cd && x.stretch == y.stretch && x.neighbour == y.neighbour)
          << "rank " << i + 1 << ", " << threads << " threads";
    }
  }
}
