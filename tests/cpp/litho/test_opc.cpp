// The emulated OPC (opc.hpp), read back through printability(): a short isolated wire, whose
// end pulls back and whose width is off when drawn, prints at its drawn length and width after
// it; lines already on target stay; the error falls; threads, ring orientation and slanted
// polygons change nothing they should not; bad input is refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "linf/litho/calibration.hpp"
#include "linf/litho/opc.hpp"
#include "linf/litho/optics.hpp"
#include "linf/litho/printability.hpp"
#include "litho/litho_fixtures.hpp"

using namespace linf;
using namespace linf::litho;
using litho_test::box;

namespace {

// The euv preset as the commands use it: its kernels, its resist blur, the threshold at which
// 22 nm lines at a 64 nm pitch print at 22 nm.
constexpr double kWidth = 22, kPitch = 64, kBlur = 5;

const Kernels& euv() {
  static const Kernels k = kernels_from_optics(optics_preset("euv"));
  return k;
}
double threshold() {
  static const double t = calibrate_threshold(euv(), kWidth, kPitch, kBlur).threshold;
  return t;
}

OpcResult correct(const std::vector<Polygon>& layer, int threads = 0, int iterations = 6) {
  const PolygonArrays flat = flat_of(layer);
  OpcRules rules;
  rules.width = kWidth;
  rules.iterations = iterations;
  return correct_mask(flat.view(), 1.0, OpcModel{&euv(), threshold(), kBlur}, rules, threads);
}

// Printed widths along measurement lines of length cd through (x, y) (DBU), nominal dose and
// focus, on a mask whose points are in DBU / scale.
using Lines = std::vector<std::array<double, 3>>;
std::vector<double> printed(const FlatPolygons& mask, std::int64_t scale, const Lines& along_x, const Lines& along_y) {
  const double S = double(scale);
  std::vector<double> cx, cy, x1, y1, x2, y2, cd;
  std::vector<std::int32_t> type;
  for (int axis = 0; axis < 2; ++axis)
    for (auto [x, y, c] : axis == 0 ? along_x : along_y) {
      x *= S, y *= S, c *= S;
      cx.push_back(x), cy.push_back(y), cd.push_back(c), type.push_back(0);
      x1.push_back(axis == 0 ? x - c / 2 : x), y1.push_back(axis == 0 ? y : y - c / 2);
      x2.push_back(axis == 0 ? x + c / 2 : x), y2.push_back(axis == 0 ? y : y + c / 2);
    }
  auto col = [](const auto& v) {
    using T = typename std::decay_t<decltype(v)>::value_type;
    return Strided<T>{reinterpret_cast<const char*>(v.data()), std::ptrdiff_t(sizeof(T)), v.size()};
  };
  const GaugeColumns g{col(cx), col(cy), col(x1), col(y1), col(x2), col(y2), col(type), col(cd), {}};
  PrintModel model;
  model.kernels = &euv();
  model.threshold = threshold();
  model.blur = kBlur;
  return printability(mask, 1.0 / S, g, model, 1).printed_cd;
}

double area(const std::int64_t* p, std::size_t n) {
  double a = 0;
  for (std::size_t j = 0; j < n; ++j) {
    const std::size_t k = (j + 1) % n;
    a += double(p[2 * j]) * double(p[2 * k + 1]) - double(p[2 * k]) * double(p[2 * j + 1]);
  }
  return std::abs(a) / 2;
}

}  // namespace

// Isolated wires 200 nm long, 22 nm (the calibration's width) and 16 nm wide, far apart: drawn,
// their ends pull back and the narrow one prints thinner still; after the OPC both print at
// their drawn length and width.
TEST(Opc, IsolatedWiresPrintAtTheirDrawnLengthAndWidth) {
  const std::vector<Polygon> layer{box(0, 0, 200, 22), box(0, 2000, 200, 2016)};
  const Lines length{{100, 11, 200}, {100, 2008, 200}}, width{{100, 11, 22}, {100, 2008, 16}};
  const PolygonArrays drawn = flat_of(layer);
  const std::vector<double> before = printed(drawn.view(), 1, length, width);
  const OpcResult r = correct(layer);
  const std::vector<double> after = printed(r.view(), r.scale, length, width);
  for (std::size_t k = 0; k < 2; ++k)
    std::printf("[ litho ] isolated %g x 200 nm wire under euv: printed length %.2f -> %.2f nm, "
                "width %.2f -> %.2f nm\n", width[k][2], before[k], after[k], before[2 + k], after[2 + k]);
  // The drawn wires must print visibly off, or the rest says nothing.
  for (const double v : before) ASSERT_FALSE(std::isnan(v));
  EXPECT_GT(std::abs(before[0] - 200), 6.0);
  EXPECT_GT(std::abs(before[1] - 200), 6.0);
  EXPECT_GT(std::abs(before[3] - 16), 1.5);
  EXPECT_NEAR(after[0], 200, 1.5);
  EXPECT_NEAR(after[1], 200, 1.5);
  EXPECT_NEAR(after[2], 22, 1.0);
  EXPECT_NEAR(after[3], 16, 1.0);
  EXPECT_LT(r.rms_epe.back(), r.rms_epe.front() / 2);
  EXPECT_EQ(r.rms_epe.size(), 7u);
  EXPECT_EQ(r.kept, 0u);
}

// Long lines at the calibration's width and pitch print at their width as drawn: the middle
// line's edges, far from its ends, stay where they are.
TEST(Opc, LinesOnTargetStay) {
  std::vector<Polygon> layer;
  for (int k = -4; k <= 4; ++k) layer.push_back(box(64 * k, -1500, 64 * k + 22, 1500));
  const OpcResult r = correct(layer);
  // The fifth polygon is the middle line: every point of it but its ends' lies on its drawn
  // edges, within a DBU (the corrected layer is in quarter DBU).
  ASSERT_EQ(r.scale, 4);
  std::size_t at = 0;
  for (std::size_t i = 0; i < 4; ++i) at += std::size_t(r.rings[i]);
  int seen = 0;
  for (std::int64_t j = 0; j < r.rings[4]; ++j) {
    const std::int64_t x = r.points[2 * (at + j)], y = r.points[2 * (at + j) + 1];
    if (std::abs(y) >= 4 * 1450) continue;
    ++seen;
    EXPECT_TRUE(std::abs(x - 0) <= 4 || std::abs(x - 4 * 22) <= 4) << x / 4.0 << ", " << y / 4.0;
  }
  EXPECT_GT(seen, 0) << "the middle line has no point away from its ends";
  const std::vector<double> w = printed(r.view(), r.scale, {{11, 0, 22}}, {});
  EXPECT_NEAR(w[0], 22, 0.5);
}

// The moves are read all at once an iteration: the same bytes for any number of threads; rings
// given clockwise come out as the same shapes.
TEST(Opc, SameForThreadsAndOrientation) {
  const Polygon ring{{{100, 120}, {300, 120}, {300, 300}, {100, 300}},
                     {{{140, 160}, {140, 260}, {260, 260}, {260, 160}}}};  // a hole, clockwise
  std::vector<Polygon> layer{box(0, 0, 200, 22), box(0, 60, 22, 400), box(80, 60, 300, 82), ring};
  const OpcResult one = correct(layer, 1, 3), two = correct(layer, 2, 3);
  EXPECT_EQ(one.points, two.points);
  EXPECT_EQ(one.rings, two.rings);
  std::vector<Polygon> turned = layer;
  for (Polygon& p : turned) {
    std::reverse(p.outer.begin(), p.outer.end());
    for (Ring& h : p.holes) std::reverse(h.begin(), h.end());
  }
  const OpcResult back = correct(turned, 1, 3);
  ASSERT_EQ(back.rings.size(), one.rings.size());
  std::size_t a = 0;
  for (std::size_t k = 0; k < one.rings.size(); ++k) {
    ASSERT_EQ(back.rings[k], one.rings[k]);
    const std::size_t n = std::size_t(std::abs(one.rings[k]));
    EXPECT_EQ(area(back.points.data() + 2 * a, n), area(one.points.data() + 2 * a, n)) << "ring " << k;
    a += n;
  }
  // The hole's edges moved too: its ring is not the drawn one.
  const std::size_t n = std::size_t(-one.rings.back());
  EXPECT_NE(area(one.points.data() + 2 * (a - n), n), 16 * 120.0 * 100.0);
}

// A polygon with an edge off the axes stays as drawn; the others are corrected beside it.
TEST(Opc, SlantedPolygonsStayAsDrawn) {
  const Polygon slanted{{{0, 100}, {200, 100}, {230, 122}, {0, 122}}, {}};
  const OpcResult r = correct({slanted, box(0, 0, 200, 22)}, 0, 2);
  EXPECT_EQ(r.kept, 1u);
  ASSERT_EQ(r.rings[0], 4);
  const std::vector<std::int64_t> drawn{0, 400, 800, 400, 920, 488, 0, 488};  // quarter DBU
  EXPECT_EQ(std::vector<std::int64_t>(r.points.begin(), r.points.begin() + 8), drawn);
  EXPECT_NE(r.rings[1], 4) << "the wire beside it was not corrected";
}

TEST(Opc, BadInput) {
  const PolygonArrays flat = flat_of({box(0, 0, 200, 22)});
  OpcRules ok;
  ok.width = kWidth;
  const OpcModel model{&euv(), threshold(), kBlur};
  auto refused = [&](const FlatPolygons& layer, double dbu, const OpcModel& m, const OpcRules& rules) {
    try {
      correct_mask(layer, dbu, m, rules);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what()).rfind("opc: ", 0) == 0;
    }
    return false;
  };
  const Kernels none;
  EXPECT_TRUE(refused(flat.view(), 1.0, OpcModel{&none, threshold(), kBlur}, ok));
  EXPECT_TRUE(refused(flat.view(), 1.0, OpcModel{&euv(), 0.0, kBlur}, ok));
  EXPECT_TRUE(refused(flat.view(), 1.0, OpcModel{&euv(), threshold(), -1.0}, ok));
  EXPECT_TRUE(refused(flat.view(), 0.0, model, ok));
  for (const double w : {0.0, -5.0, std::nan("")}) {
    OpcRules r = ok;
    r.width = w;
    EXPECT_TRUE(refused(flat.view(), 1.0, model, r)) << w;
  }
  for (const double f : {0.0, 1.5}) {
    OpcRules r = ok;
    r.feedback = f;
    EXPECT_TRUE(refused(flat.view(), 1.0, model, r)) << f;
  }
  OpcRules r = ok;
  r.iterations = -1;
  EXPECT_TRUE(refused(flat.view(), 1.0, model, r));
  const std::int64_t pts[] = {0, 0, 10, 0, 10, 10, 0, 10}, rings[] = {5};
  EXPECT_TRUE(refused(FlatPolygons{pts, 4, rings, 1}, 1.0, model, ok));
  EXPECT_FALSE(refused(flat.view(), 1.0, model, ok));
}
