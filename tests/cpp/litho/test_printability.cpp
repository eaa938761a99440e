// Printability of gauges through the layer-level API (printability.hpp): the same printed width
// as the resist alone on a hand-made clip, a neck that pinches, a gap that bridges, one
// simulation a context, the 8 transforms of a clip, bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "linf/litho/printability.hpp"
#include "linf/litho/resist.hpp"
#include "litho/litho_fixtures.hpp"

using namespace linf;
using namespace linf::litho;
using litho_test::box;
using litho_test::focus;

namespace {

constexpr double T = kIccad13Threshold;
constexpr int kInternal = 0, kExternal = 1;

// Gauges as plain vectors, handed to the core as columns.
struct Gauges {
  std::vector<double> cx, cy, x1, y1, x2, y2, cd;
  std::vector<std::int32_t> type;
  std::vector<std::uint64_t> context;
  // A measurement line of length cd through (x, y), along x or along y.
  void add(double x, double y, bool along_x, double cd_, int t, std::uint64_t ctx = 0) {
    cx.push_back(x), cy.push_back(y), cd.push_back(cd_), type.push_back(t), context.push_back(ctx);
    const double h = cd_ / 2;
    x1.push_back(along_x ? x - h : x), y1.push_back(along_x ? y : y - h);
    x2.push_back(along_x ? x + h : x), y2.push_back(along_x ? y : y + h);
  }
  template <class V>
  static Strided<typename V::value_type> col(const V& v) {
    return {reinterpret_cast<const char*>(v.data()), std::ptrdiff_t(sizeof(typename V::value_type)), v.size()};
  }
  GaugeColumns columns(bool with_context) const {
    GaugeColumns g{col(cx), col(cy), col(x1), col(y1), col(x2), col(y2), col(type), col(cd), {}};
    if (with_context) g.context = col(context);
    return g;
  }
};

// Line ends of 120 nm wires facing across a gap closed 10 nm at a time (200 down to 10 nm), one
// row a gap, each with an external gauge along the wires across its gap.
struct LineEndGaps {
  std::vector<Polygon> layer;
  Gauges g;
  std::vector<int> gaps;
  LineEndGaps() {
    for (int gap = 200, k = 0; gap >= 10; gap -= 10, ++k) {
      const Coord y = 3000 * k, a = 1000 - gap / 2;
      layer.push_back(box(300, y, a, y + 120));
      layer.push_back(box(a + gap, y, 1700, y + 120));
      g.add(a + gap / 2.0, y + 60, true, gap, kExternal);
      gaps.push_back(gap);
    }
  }
};

Printability run(const std::vector<Polygon>& layer, const Gauges& g, bool with_context = false, int threads = 0,
                 double threshold = T) {
  const PolygonArrays flat = flat_of(layer);
  return printability(flat.view(), 1.0, g.columns(with_context), PrintModel{&focus(), threshold}, threads);
}

}  // namespace

// A 100 nm line with a wire beyond it that crosses the window's side: the API's printed width
// is what the resist alone reads on the same clip made by hand (window corner at the gauge
// point minus 1024 nm, the wire cut at the window's side).
TEST(Printability, ConsistentWithTheResistOnTheSameClip) {
  const std::vector<Polygon> layer{box(9950, 9500, 10050, 10200), box(0, 10300, 20000, 10400)};
  Gauges g;
  g.add(10000, 9800, true, 100, kInternal);
  g.add(10000, 10250, false, 100, kExternal);  // the space between the line's end and the wire
  const Printability p = run(layer, g);
  const Window w{{10000 - 1024, 9800 - 1024}, 1.0};
  const std::vector<Polygon> clip{box(9950, 9500, 10050, 10200), box(10000 - 1024, 10300, 10000 + 1024, 10400)};
  const AerialImage im(focus(), MaskSpectrum(clip, w, 2048, focus().half()));
  const Cut want = measure(LineProfile(im, 1024, 1024, 1, 0), T, Across::printed, 512);
  ASSERT_EQ(want.outcome, Cut::Outcome::measured);
  EXPECT_NEAR(p.printed_cd[0], want.width, 1e-9);
  EXPECT_NEAR(p.score[0], want.width / 100, 1e-12);
  EXPECT_EQ(p.fails[0], Fail::none);
  EXPECT_GT(want.width, 60.0);
  EXPECT_LT(want.width, 140.0);
  // The second gauge's own window (corner at its point minus 1024).
  const Window w2{{10000 - 1024, 10250 - 1024}, 1.0};
  const std::vector<Polygon> clip2{box(9950, 9500, 10050, 10200), box(10000 - 1024, 10300, 10000 + 1024, 10400)};
  const AerialImage im2(focus(), MaskSpectrum(clip2, w2, 2048, focus().half()));
  const Cut space = measure(LineProfile(im2, 1024, 1024, 0, 1), T, Across::clear, 512);
  if (space.outcome == Cut::Outcome::measured) {
    EXPECT_NEAR(p.printed_cd[1], space.width, 1e-9);
  } else {
    EXPECT_TRUE(std::isnan(p.printed_cd[1]));
    EXPECT_EQ(p.fails[1], space.outcome == Cut::Outcome::bridge ? Fail::bridge : Fail::none);
  }
  EXPECT_EQ(p.simulations, 2u);
  EXPECT_EQ(p.shared, 0u);
}

// Necks of 200 nm in 120 nm wires, narrowed 10 nm at a time, all on one layer (one gauge each,
// across the neck's middle): measured and narrowing, then `pinch` for every narrower neck, with
// a negative score (failures first); the measured ones score above 0.
TEST(Printability, NarrowedLinePinches) {
  std::vector<Polygon> layer;
  Gauges g;
  std::vector<int> necks;
  for (int n = 120, k = 0; n >= 20; n -= 10, ++k) {
    const Coord y = 3000 * k;  // windows 2048 nm apart never see each other's wires
    const Coord a = 60 - n / 2;  // the neck's left side, x from 0 .. 120
    layer.push_back(Polygon{{{0, y}, {120, y}, {120, y + 700}, {a + n, y + 700}, {a + n, y + 900}, {120, y + 900},
                             {120, y + 1600}, {0, y + 1600}, {0, y + 900}, {a, y + 900}, {a, y + 700}, {0, y + 700}},
                            {}});
    g.add(a + n / 2.0, y + 800, true, n, kInternal);
    necks.push_back(n);
  }
  const Printability p = run(layer, g);
  bool pinched = false;
  double last = 1e9;
  for (std::size_t i = 0; i < necks.size(); ++i) {
    if (pinched) {
      EXPECT_EQ(p.fails[i], Fail::pinch) << necks[i];
      continue;
    }
    if (p.fails[i] == Fail::pinch) {
      pinched = true;
      EXPECT_TRUE(std::isnan(p.printed_cd[i]));
      EXPECT_LE(p.score[i], 0.0);
      EXPECT_GE(p.score[i], -1.0);
      std::printf("[ litho ] gauge on a neck of a 120 nm wire: pinch at %d nm\n", necks[i]);
      continue;
    }
    ASSERT_EQ(p.fails[i], Fail::none) << necks[i];
    EXPECT_LT(p.printed_cd[i], last) << necks[i];
    EXPECT_GT(p.score[i], 0.0);
    last = p.printed_cd[i];
  }
  EXPECT_TRUE(pinched);
  EXPECT_EQ(p.fails.front(), Fail::none);
}

// Line ends of 120 nm wires facing across a gap closed 10 nm at a time: the external gauge
// along the wires is measured, then `bridge`.
TEST(Printability, ClosedGapBridges) {
  const LineEndGaps ends;
  const std::vector<Polygon>& layer = ends.layer;
  const Gauges& g = ends.g;
  const std::vector<int>& gaps = ends.gaps;
  const Printability p = run(layer, g);
  bool bridged = false;
  for (std::size_t i = 0; i < gaps.size(); ++i) {
    if (bridged) {
      EXPECT_EQ(p.fails[i], Fail::bridge) << gaps[i];
      continue;
    }
    if (p.fails[i] == Fail::bridge) {
      bridged = true;
      EXPECT_LE(p.score[i], 0.0);
      std::printf("[ litho ] gauge on a line-end gap of 120 nm wires: bridge at %d nm\n", gaps[i]);
      continue;
    }
    ASSERT_EQ(p.fails[i], Fail::none) << gaps[i];
    EXPECT_GT(p.score[i], 0.0);
  }
  EXPECT_TRUE(bridged);
  EXPECT_EQ(p.fails.front(), Fail::none);
}

// The process window on the same necks and gaps with the contest's corners (dose 0.98 with the
// defocused kernels, 1.02 in focus): every neck that pinches at nominal pinches in the window,
// and the window pinches a wider neck first (the inner corner prints thinner); likewise a gap
// bridges wider in the window (the outer corner prints fatter). Where the nominal reading is
// measured and no corner fails, pv_band is the outer minus the inner width (> 0, below the
// nominal width for a neck); where only the inner corner pinches, pv_band is the outer width,
// at least the nominal one. The score is the least over the conditions, so never above the
// nominal ratio. dose = 0 leaves pv_band NaN and fails equal to fails_nominal.
TEST(Printability, ProcessWindowCorners) {
  static const Kernels defocus = read_kernels(litho_test::shipped("M1OPC_def"));
  std::vector<Polygon> layer;
  Gauges g;
  std::vector<int> sizes;
  int k = 0;
  for (int n = 120; n >= 20; n -= 5, ++k) {
    const Coord y = 3000 * k;
    const Coord a = 60 - n / 2;
    layer.push_back(Polygon{{{0, y}, {120, y}, {120, y + 700}, {a + n, y + 700}, {a + n, y + 900}, {120, y + 900},
                             {120, y + 1600}, {0, y + 1600}, {0, y + 900}, {a, y + 900}, {a, y + 700}, {0, y + 700}},
                            {}});
    g.add(a + n / 2.0, y + 800, true, n, kInternal);
    sizes.push_back(n);
  }
  const std::size_t necks = sizes.size();
  for (int gap = 120; gap >= 10; gap -= 5, ++k) {
    const Coord y = 3000 * k, a = 1000 - gap / 2;
    layer.push_back(box(300, y, a, y + 120));
    layer.push_back(box(a + gap, y, 1700, y + 120));
    g.add(a + gap / 2.0, y + 60, true, gap, kExternal);
    sizes.push_back(gap);
  }
  const PolygonArrays flat = flat_of(layer);
  const Printability nominal = printability(flat.view(), 1.0, g.columns(false), PrintModel{&focus(), T}, 0);
  const Printability pw =
      printability(flat.view(), 1.0, g.columns(false), PrintModel{&focus(), T, &defocus, 0.02}, 0);
  int first_nominal[2] = {-1, -1}, first_window[2] = {-1, -1};
  int corner_only = 0, measured_both = 0;
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    const int kind = i < necks ? 0 : 1;
    const Fail want = kind == 0 ? Fail::pinch : Fail::bridge;
    EXPECT_EQ(nominal.fails[i], pw.fails_nominal[i]) << sizes[i];
    EXPECT_EQ(nominal.fails[i], nominal.fails_nominal[i]);
    EXPECT_TRUE(std::isnan(nominal.pv_band[i]));
    EXPECT_TRUE(pw.fails[i] == Fail::none || pw.fails[i] == want) << sizes[i];
    if (nominal.fails[i] != Fail::none) {
      EXPECT_EQ(pw.fails[i], want) << sizes[i];
    }
    if (nominal.fails[i] != Fail::none && first_nominal[kind] < 0) first_nominal[kind] = sizes[i];
    if (pw.fails[i] != Fail::none && first_window[kind] < 0) first_window[kind] = sizes[i];
    EXPECT_LE(pw.score[i], nominal.score[i] + 1e-12) << sizes[i];
    EXPECT_EQ(pw.fails[i] != Fail::none, pw.score[i] <= 0) << sizes[i];
    if (nominal.fails[i] == Fail::none && pw.fails[i] == Fail::none) {
      ++measured_both;
      EXPECT_GT(pw.pv_band[i], 0.0) << sizes[i];
      EXPECT_NEAR(pw.printed_cd[i], nominal.printed_cd[i], 1e-12);
      if (kind == 0) EXPECT_LT(pw.pv_band[i], pw.printed_cd[i]) << sizes[i];
    }
    if (nominal.fails[i] == Fail::none && pw.fails[i] != Fail::none) {
      ++corner_only;
      EXPECT_GE(pw.pv_band[i], pw.printed_cd[i] - 1e-9) << sizes[i];
    }
  }
  std::printf("[ litho ] neck pinches at %d nm nominal, %d nm in the window; gap bridges at %d nm nominal, %d nm "
              "in the window; %d gauges fail at a corner only\n",
              first_nominal[0], first_window[0], first_nominal[1], first_window[1], corner_only);
  EXPECT_GT(first_window[0], first_nominal[0]);
  EXPECT_GT(first_window[1], first_nominal[1]);
  EXPECT_GT(corner_only, 0);
  EXPECT_GT(measured_both, 10);
  // A dose-only window (no defocus kernels) still widens the failures, less or as much.
  const Printability dose_only =
      printability(flat.view(), 1.0, g.columns(false), PrintModel{&focus(), T, nullptr, 0.02}, 0);
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    if (dose_only.fails[i] != Fail::none) EXPECT_NE(pw.fails[i], Fail::none) << sizes[i];
  }
  // Bad process window input.
  Kernels small = focus();
  small.size = 33;
  EXPECT_THROW(printability(flat.view(), 1.0, g.columns(false), PrintModel{&focus(), T, &small, 0.02}, 0),
               std::invalid_argument);
  EXPECT_THROW(printability(flat.view(), 1.0, g.columns(false), PrintModel{&focus(), T, nullptr, -0.1}, 0),
               std::invalid_argument);
}

// The resist's blur closes narrow gaps sooner: on the line-end gaps above, every gap that
// bridges bare bridges blurred, and the blurred model bridges a wider one. A negative blur is
// refused.
TEST(Printability, BlurBridgesWiderGaps) {
  const LineEndGaps ends;
  const std::vector<Polygon>& layer = ends.layer;
  const Gauges& g = ends.g;
  const std::vector<int>& gaps = ends.gaps;
  const PolygonArrays flat = flat_of(layer);
  const Printability bare = printability(flat.view(), 1.0, g.columns(false), PrintModel{&focus(), T}, 0);
  const Printability blurred =
      printability(flat.view(), 1.0, g.columns(false), PrintModel{&focus(), T, nullptr, 0, 40}, 0);
  int widest_bare = 0, widest_blurred = 0;
  for (std::size_t i = 0; i < gaps.size(); ++i) {
    if (bare.fails[i] == Fail::bridge) EXPECT_EQ(blurred.fails[i], Fail::bridge) << gaps[i];
    if (bare.fails[i] == Fail::bridge) widest_bare = std::max(widest_bare, gaps[i]);
    if (blurred.fails[i] == Fail::bridge) widest_blurred = std::max(widest_blurred, gaps[i]);
  }
  std::printf("[ litho ] line-end gap of 120 nm wires bridges up to %d nm bare, %d nm with a 40 nm blur\n", widest_bare,
              widest_blurred);
  EXPECT_GT(widest_blurred, widest_bare);
  EXPECT_THROW(printability(flat.view(), 1.0, g.columns(false), PrintModel{&focus(), T, nullptr, 0, -1}, 0),
               std::invalid_argument);
}

// Five copies of one pattern, far apart, each with a width and a space gauge. With one context
// id for the copies: one simulation per type (2), eight gauges shared, and the same results
// as simulating every copy (10 simulations), which the copies being translates must give.
TEST(Printability, OneSimulationAContext) {
  std::vector<Polygon> layer;
  Gauges g;
  for (int k = 0; k < 5; ++k) {
    const Coord x = 5000 * k;
    layer.push_back(box(x + 900, 500, x + 990, 1500));
    layer.push_back(box(x + 1090, 500, x + 1180, 1500));
    g.add(x + 945, 1000, true, 90, kInternal, 7);
    g.add(x + 1040, 1000, true, 100, kExternal, 7);
  }
  const Printability shared = run(layer, g, true), each = run(layer, g, false);
  EXPECT_EQ(shared.simulations, 2u);
  EXPECT_EQ(shared.shared, 8u);
  EXPECT_EQ(each.simulations, 10u);
  EXPECT_EQ(each.shared, 0u);
  for (std::size_t i = 0; i < g.cx.size(); ++i) {
    ASSERT_EQ(shared.fails[i], Fail::none) << i;
    EXPECT_NEAR(shared.printed_cd[i], each.printed_cd[i], 1e-9) << i;
    EXPECT_EQ(shared.printed_cd[i], shared.printed_cd[i % 2]) << i;  // read from the first copy
  }
  // A third id: one more simulation.
  g.context[4] = 8;
  EXPECT_EQ(run(layer, g, true).simulations, 3u);
}

// Gauges of several types on one line (one point, one direction; contexts of their own) are
// read on one image each by its type, as if alone: two widths share the image and the reading
// (their drawn cds differ, so their scores do), a gauge across them takes another image.
TEST(Printability, GaugesOnOneLineShareItsImage) {
  const std::vector<Polygon> layer{box(900, 500, 990, 1500), box(1090, 500, 1180, 1500)};
  Gauges g;
  g.add(945, 1000, true, 90, kInternal, 1);
  g.add(945, 1000, true, 60, 2, 2);          // a sandwich's line across the same feature
  g.add(945, 1000, false, 90, kInternal, 3);  // along the line: another direction
  const Printability together = run(layer, g, true);
  EXPECT_EQ(together.simulations, 3u);
  EXPECT_EQ(together.images, 2u);
  for (std::size_t i = 0; i < 3; ++i) {
    Gauges one;
    one.add(g.cx[i], g.cy[i], g.x1[i] != g.x2[i], g.cd[i], g.type[i]);
    const Printability alone = run(layer, one);
    EXPECT_EQ(alone.images, 1u);
    EXPECT_EQ(together.fails[i], alone.fails[0]) << i;
    EXPECT_EQ(together.score[i], alone.score[0]) << i;
    if (!std::isnan(alone.printed_cd[0])) EXPECT_EQ(together.printed_cd[i], alone.printed_cd[0]) << i;
    else EXPECT_TRUE(std::isnan(together.printed_cd[i])) << i;
  }
  ASSERT_EQ(together.fails[0], Fail::none);
  EXPECT_EQ(together.printed_cd[0], together.printed_cd[1]);
  EXPECT_NE(together.score[0], together.score[1]);
}

// A gauge's printed CD through this API is the same under the 8 transforms of the layer about
// the gauge point, to the bound of part 1 (test_resist.cpp): the image's symmetry defect times
// the clip's spectral energy, over the image's slope at each edge.
TEST(Printability, SameUnderTheSquaresTransforms) {
  const Coord cx = 40000, cy = 30000;  // the gauge points: on the first line, and in the space
  const std::vector<Polygon> base{box(cx - 45, cy - 400, cx + 45, cy + 450), box(cx + 135, cy - 400, cx + 225, cy + 200),
                                  Polygon{{{cx + 315, cy - 300}, {cx + 655, cy - 300}, {cx + 655, cy - 210},
                                           {cx + 405, cy - 210}, {cx + 405, cy + 300}, {cx + 315, cy + 300}},
                                          {}},
                                  box(cx - 2000, cy + 900, cx + 2000, cy + 990)};  // crosses the window's sides
  struct G {
    double dx, dy;  // the gauge point's offset from (cx, cy)
    double cd;
    int type;
  };
  const std::vector<G> gauges{{0, 0, 90, kInternal}, {90, 0, 90, kExternal}};
  double worst = 0;
  for (const G& ga : gauges) {
    Gauges one;
    one.add(cx + ga.dx, cy, true, ga.cd, ga.type);
    const double want = run(base, one).printed_cd[0];
    ASSERT_FALSE(std::isnan(want));
    // The bound, from the untransformed clip in the gauge's window (the wire cut at its sides).
    const Coord ox = cx + Coord(ga.dx) - 1024, oy = cy - 1024;
    std::vector<Polygon> clip = base;
    clip[3] = box(ox, cy + 900, ox + 2048, cy + 990);
    const MaskSpectrum spectrum(clip, Window{{ox, oy}, 1.0}, 2048, focus().half());
    double energy = 0;
    for (int kx = -17; kx <= 17; ++kx)
      for (int ky = -17; ky <= 17; ++ky) energy += std::norm(spectrum.at(kx, ky));
    const double image_bound = litho_test::tcc_symmetry_defect(focus()) * energy;
    const AerialImage im(focus(), spectrum);
    const LineProfile line(im, 1024, 1024, 1, 0);
    const Cut cut = measure(line, T, ga.type == kExternal ? Across::clear : Across::printed, 512);
    ASSERT_EQ(cut.outcome, Cut::Outcome::measured);
    EXPECT_NEAR(cut.width, want, 1e-9);
    auto slope = [&](double t) { return (line.at(t + 0.01) - line.at(t - 0.01)) / 0.02; };
    const double tol = image_bound / std::abs(slope(cut.lo)) + image_bound / std::abs(slope(cut.hi));
    double here = 0;
    for (int swap = 0; swap < 2; ++swap)
      for (int sx = -1; sx <= 1; sx += 2)
        for (int sy = -1; sy <= 1; sy += 2) {
          auto tx = [&](double x, double y) { return cx + sx * ((swap ? y - cy : x - cx)); };
          auto ty = [&](double x, double y) { return cy + sy * ((swap ? x - cx : y - cy)); };
          std::vector<Polygon> moved = base;
          for (auto& p : moved)
            for (auto& q : p.outer) q = Point{Coord(tx(double(q.x), double(q.y))), Coord(ty(double(q.x), double(q.y)))};
          Gauges t;
          const double px = cx + ga.dx, py = cy;
          t.cx = {tx(px, py)}, t.cy = {ty(px, py)}, t.cd = {ga.cd}, t.type = {ga.type}, t.context = {0};
          t.x1 = {tx(px - ga.cd / 2, py)}, t.y1 = {ty(px - ga.cd / 2, py)};
          t.x2 = {tx(px + ga.cd / 2, py)}, t.y2 = {ty(px + ga.cd / 2, py)};
          const Printability got = run(moved, t);
          ASSERT_EQ(got.fails[0], Fail::none);
          EXPECT_NEAR(got.printed_cd[0], want, tol) << "swap " << swap << " sx " << sx << " sy " << sy;
          here = std::max(here, std::abs(got.printed_cd[0] - want));
        }
    std::printf("[ litho ] gauge (type %d) under 8 transforms: printed %.4f nm, max difference %.3g nm, bound %.3g nm\n",
                ga.type, want, here, tol);
    worst = std::max(worst, here);
  }
  EXPECT_GT(worst, 0.0);  // the transforms were applied (the layer has no symmetry)
}

// Bad input: a clear error, nothing computed.
TEST(Printability, BadInput) {
  const std::vector<Polygon> layer{box(0, 0, 100, 1000)};
  auto message = [&](const Gauges& g, double threshold = T) {
    try {
      run(layer, g, false, 0, threshold);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  Gauges outside;
  outside.add(50, 500, true, 100, kInternal);
  outside.x2[0] = 50 + 1100;  // beyond the 2048 nm window centred on the point
  EXPECT_NE(message(outside).find("reaches outside its window"), std::string::npos) << message(outside);
  Gauges flat;
  flat.add(50, 500, true, 100, kInternal);
  flat.x2[0] = flat.x1[0];
  EXPECT_NE(message(flat).find("no length"), std::string::npos) << message(flat);
  Gauges zero;
  zero.add(50, 500, true, 0, kInternal);
  EXPECT_NE(message(zero).find("cd is not positive"), std::string::npos) << message(zero);
  Gauges ok;
  ok.add(50, 500, true, 100, kInternal);
  EXPECT_NE(message(ok, 0).find("threshold"), std::string::npos);
  ok.cd.pop_back();
  EXPECT_NE(message(ok).find("different lengths"), std::string::npos) << message(ok);
  EXPECT_THROW(printability(flat_of(layer).view(), 1.0, outside.columns(false), PrintModel{}, 0), std::invalid_argument);
}

// A gauge point at a half DBU (a line of odd width) has its window centred exactly on it: the
// same layer moved by whole DBU, to either side of the origin, reads the same to 1e-9 nm (a
// corner rounded to the DBU grid would move the window by half a unit one way or the other
// with the point's sign, and the wire cut at its sides with it).
TEST(Printability, HalfDbuPointsAreCentredExactly) {
  std::vector<double> got;
  for (const Coord dx : {Coord(0), Coord(70001), Coord(-70001), Coord(-300000)}) {
    const std::vector<Polygon> layer{box(dx + 0, 0, dx + 91, 1000), box(dx - 3000, 1100, dx + 500, 1190)};  // crosses one side
    Gauges g;
    g.add(dx + 45.5, 500, true, 91, kInternal);
    g.add(dx + 45.5, 1050, false, 100, kExternal);
    const Printability p = run(layer, g);
    ASSERT_EQ(p.fails[0], Fail::none);
    got.push_back(p.printed_cd[0]);
    got.push_back(p.printed_cd[1]);
  }
  for (std::size_t i = 2; i < got.size(); ++i) EXPECT_NEAR(got[i], got[i % 2], 1e-9) << i;
}

// The batch's Dask tasks (cluster.Tiles.printability): gauges read in chunks, each on the part
// of the layer its windows meet (window_shapes), give the same bytes as on the whole layer. Line
// pairs 1 um apart put neighbours across every window's sides; the parts also hold a hole, a
// slanted edge and a wire crossing every window, and leave out what no window of theirs meets.
TEST(Printability, ChunksReadOnTheirPartsAsOnTheLayer) {
  std::vector<Polygon> layer;
  Gauges g;
  for (int k = 0; k < 10; ++k) {  // widths 60 to 150 nm, spaces 100 nm
    const Coord x = 1000 * k, w = 60 + 10 * k;
    layer.push_back(box(x + 100, 500, x + 100 + w, 1500));
    layer.push_back(box(x + 200 + w, 500, x + 200 + 2 * w, 1500));
    g.add(x + 100 + w / 2.0, 1000, true, double(w), kInternal);
    g.add(x + 150 + w, 1000, true, 100, kExternal);
  }
  layer.push_back(box(0, 1900, 10000, 1990));  // within every pair's window, across its sides
  Polygon ring = box(12000, 400, 12600, 1600);
  ring.holes.push_back({{12100, 500}, {12100, 1500}, {12500, 1500}, {12500, 500}});
  layer.push_back(ring);
  g.add(12050, 1000, true, 100, kInternal);  // across the ring's left wall
  layer.push_back(Polygon{{{15000, 500}, {15200, 500}, {15900, 1500}, {15700, 1500}}, {}});
  g.add(15450, 1000, true, 200, kInternal);  // across the slanted bar
  const PolygonArrays flat = flat_of(layer);
  const PrintModel model{&focus(), T};
  const Printability whole = printability(flat.view(), 1.0, g.columns(false), model, 1);
  const std::vector<std::size_t> starts{0, 5, 13, g.cx.size()};
  const std::vector<LayerPart> parts =
      window_shapes(flat.view(), 1.0, focus().period, Gauges::col(g.cx), Gauges::col(g.cy), starts);
  ASSERT_EQ(parts.size(), 3u);
  std::size_t images = 0, measured = 0;
  for (std::size_t c = 0; c < parts.size(); ++c) {
    Gauges sub;
    std::size_t meet = 0;  // the polygons whose boxes meet a window of the chunk (side 2048 nm)
    for (const Polygon& q : layer) {
      Coord lx = q.outer[0].x, hx = lx, ly = q.outer[0].y, hy = ly;
      for (const Point& v : q.outer) lx = std::min(lx, v.x), hx = std::max(hx, v.x), ly = std::min(ly, v.y), hy = std::max(hy, v.y);
      bool any = false;
      for (std::size_t i = starts[c]; i < starts[c + 1]; ++i)
        any = any || (lx <= g.cx[i] + 1024 && hx >= g.cx[i] - 1024 && ly <= g.cy[i] + 1024 && hy >= g.cy[i] - 1024);
      meet += any;
    }
    for (std::size_t i = starts[c]; i < starts[c + 1]; ++i) {
      sub.cx.push_back(g.cx[i]), sub.cy.push_back(g.cy[i]), sub.x1.push_back(g.x1[i]), sub.y1.push_back(g.y1[i]);
      sub.x2.push_back(g.x2[i]), sub.y2.push_back(g.y2[i]), sub.cd.push_back(g.cd[i]), sub.type.push_back(g.type[i]);
    }
    const Printability p = printability(parts[c].view(), 1.0, sub.columns(false), model, 1);
    images += p.images;
    for (std::size_t j = 0; j < sub.cx.size(); ++j) {
      const std::size_t i = starts[c] + j;
      EXPECT_EQ(std::memcmp(&p.printed_cd[j], &whole.printed_cd[i], sizeof(double)), 0) << i;
      EXPECT_EQ(std::memcmp(&p.score[j], &whole.score[i], sizeof(double)), 0) << i;
      EXPECT_EQ(p.fails[j], whole.fails[i]) << i;
      measured += !std::isnan(p.printed_cd[j]);
    }
    std::size_t outer = 0, holes = 0;
    for (const std::int64_t r : parts[c].rings) (r > 0 ? outer : holes) += 1;
    EXPECT_EQ(outer, meet) << c;
    EXPECT_LT(outer, layer.size()) << c;  // a part is not the layer
    EXPECT_EQ(holes, c == 2 ? 1u : 0u) << c;
  }
  EXPECT_EQ(images, whole.images);
  EXPECT_GT(measured, g.cx.size() / 2);
  EXPECT_THROW(window_shapes(flat.view(), 1.0, focus().period, Gauges::col(g.cx), Gauges::col(g.cy), {0, 9, 4}),
               std::invalid_argument);
}
