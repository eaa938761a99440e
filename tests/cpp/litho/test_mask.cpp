// The mask's exact spectrum: boxes against the closed form, edges at any angle, holes,
// orientation, the window's origin and unit, the square's transforms, and polygons outside.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>
#include <vector>

#include "linf/litho/mask.hpp"
#include "litho/litho_fixtures.hpp"

using namespace linf;
using namespace linf::litho;
using litho_test::box;
using cd = std::complex<double>;

namespace {

constexpr double P = 2048;
constexpr int H = 17;
const double kPi = std::acos(-1.0);

// integral from a to b of exp(-2 pi i k x / P) dx, written out.
cd line_integral(int k, double a, double b) {
  if (k == 0) return b - a;
  const double w = 2 * kPi * k / P;
  return (std::polar(1.0, -w * a) - std::polar(1.0, -w * b)) / cd(0, w);
}

double max_difference(const MaskSpectrum& a, const MaskSpectrum& b) {
  double worst = 0;
  for (int kx = -H; kx <= H; ++kx)
    for (int ky = -H; ky <= H; ++ky) worst = std::max(worst, std::abs(a.at(kx, ky) - b.at(kx, ky)));
  return worst;
}

MaskSpectrum spectrum(const std::vector<Polygon>& ps) { return MaskSpectrum(ps, Window{}, P, H); }

Polygon reversed(Polygon p) {
  std::reverse(p.outer.begin(), p.outer.end());
  for (auto& h : p.holes) std::reverse(h.begin(), h.end());
  return p;
}

}  // namespace

TEST(MaskSpectrum, BoxIsAProductOfSincs) {
  const MaskSpectrum m = spectrum({box(300, 1000, 460, 1900)});
  double worst = 0;
  for (int kx = -H; kx <= H; ++kx)
    for (int ky = -H; ky <= H; ++ky) {
      const cd want = line_integral(kx, 300, 460) * line_integral(ky, 1000, 1900) / (P * P);
      worst = std::max(worst, std::abs(m.at(kx, ky) - want));
    }
  EXPECT_LT(worst, 1e-15);
  EXPECT_NEAR(m.at(0, 0).real(), 160.0 * 900.0 / (P * P), 1e-15);  // the area fraction
}

TEST(MaskSpectrum, OrientationHolesAndSums) {
  Polygon ring = box(200, 200, 1800, 1600);
  ring.holes.push_back(box(500, 400, 900, 1200).outer);
  const MaskSpectrum with_hole = spectrum({ring});
  // Either orientation of either ring: the same mask.
  EXPECT_LT(max_difference(with_hole, spectrum({reversed(ring)})), 1e-15);
  Polygon mixed = ring;
  std::reverse(mixed.holes[0].begin(), mixed.holes[0].end());
  EXPECT_LT(max_difference(with_hole, spectrum({mixed})), 1e-15);
  // A hole is the outer box minus the hole's box; two polygons add.
  const MaskSpectrum outer = spectrum({box(200, 200, 1800, 1600)}), hole = spectrum({box(500, 400, 900, 1200)});
  const MaskSpectrum both = spectrum({ring, box(0, 1700, 2048, 2048)}), strip = spectrum({box(0, 1700, 2048, 2048)});
  for (int kx = -H; kx <= H; ++kx)
    for (int ky = -H; ky <= H; ++ky) {
      EXPECT_LT(std::abs(with_hole.at(kx, ky) - (outer.at(kx, ky) - hole.at(kx, ky))), 1e-15);
      EXPECT_LT(std::abs(both.at(kx, ky) - (with_hole.at(kx, ky) + strip.at(kx, ky))), 1e-15);
    }
  // Empty: all zero; the whole window: 1 at zero frequency and nothing else.
  EXPECT_EQ(max_difference(spectrum({}), spectrum({Polygon{{{5, 5}, {9, 5}}, {}}})), 0.0);
  const MaskSpectrum full = spectrum({box(0, 0, 2048, 2048)});
  for (int kx = -H; kx <= H; ++kx)
    for (int ky = -H; ky <= H; ++ky)
      EXPECT_NEAR(std::abs(full.at(kx, ky) - (kx == 0 && ky == 0 ? 1.0 : 0.0)), 0.0, 1e-15) << kx << " " << ky;
}

// Edges at any angle: a box cut along a diagonal into two triangles has the box's spectrum,
// and a polygon of 30-degree edges keeps its area.
TEST(MaskSpectrum, EdgesAtAnyAngle) {
  const MaskSpectrum whole = spectrum({box(100, 200, 700, 500)});
  const Polygon lower{{{100, 200}, {700, 200}, {700, 500}}, {}}, upper{{{100, 200}, {700, 500}, {100, 500}}, {}};
  EXPECT_LT(max_difference(whole, spectrum({lower, upper})), 1e-15);
  // Any slope: a hexagon-like ring with slanted edges, split by a vertical cut into two.
  const Polygon left{{{400, 300}, {1000, 650}, {1000, 1453}, {613, 1700}, {300, 900}}, {}};
  const Polygon right{{{1000, 650}, {1571, 300}, {1900, 1100}, {1000, 1453}}, {}};
  const Polygon joined{{{400, 300}, {1000, 650}, {1571, 300}, {1900, 1100}, {1000, 1453}, {613, 1700}, {300, 900}}, {}};
  EXPECT_LT(max_difference(spectrum({joined}), spectrum({left, right})), 1e-15);
  double twice = 0;
  for (std::size_t i = 0, n = joined.outer.size(); i < n; ++i) {
    const Point a = joined.outer[i], b = joined.outer[(i + 1) % n];
    twice += double(a.x) * double(b.y) - double(b.x) * double(a.y);
  }
  EXPECT_NEAR(spectrum({joined}).at(0, 0).real(), std::abs(twice) / 2 / (P * P), 1e-15);
  // A sheared box, x from x0 + s y' to x0 + L + s y' over y' = y - y0 in [0, height], has the
  // closed form phi(a; x0, x0 + L) exp(-i b y0) integral from 0 to height of exp(-i (a s + b) y') dy'.
  for (const int shift : {200, -300, 1}) {
    const double x0 = 700, L = 150, y0 = 800, height = 400, s = shift / height;
    const Polygon sheared{{{700, 800}, {850, 800}, {Coord(850 + shift), 1200}, {Coord(700 + shift), 1200}}, {}};
    const MaskSpectrum m = spectrum({sheared});
    double worst = 0;
    for (int kx = -H; kx <= H; ++kx)
      for (int ky = -H; ky <= H; ++ky) {
        const double a = 2 * kPi * kx / P, b = 2 * kPi * ky / P, g = a * s + b;
        const cd along = std::abs(g) < 1e-12 ? cd(height) : (1.0 - std::polar(1.0, -g * height)) / cd(0, g);
        const cd want = line_integral(kx, x0, x0 + L) * std::polar(1.0, -b * y0) * along / (P * P);
        worst = std::max(worst, std::abs(m.at(kx, ky) - want));
      }
    EXPECT_LT(worst, 1e-15) << "shift " << shift;
  }
}

// A real mask's spectrum is Hermitian, c(-kx, -ky) = conj(c(kx, ky)): to the bit on Manhattan
// polygons (half of it is formed and mirrored), to rounding with a slanted edge (formed whole).
TEST(MaskSpectrum, HermitianAsTheMaskIsReal) {
  const MaskSpectrum manhattan = spectrum({box(100, 200, 700, 500), box(900, 150, 1300, 1900)});
  const Polygon slanted{{{400, 300}, {1000, 650}, {1571, 300}, {1900, 1100}, {613, 1700}}, {}};
  const MaskSpectrum any = spectrum({slanted, box(100, 1800, 300, 2000)});
  double worst = 0;
  for (int kx = -H; kx <= H; ++kx)
    for (int ky = -H; ky <= H; ++ky) {
      ASSERT_EQ(manhattan.at(-kx, -ky), std::conj(manhattan.at(kx, ky))) << kx << " " << ky;
      worst = std::max(worst, std::abs(any.at(-kx, -ky) - std::conj(any.at(kx, ky))));
    }
  EXPECT_LT(worst, 1e-16);
  EXPECT_GT(std::abs(any.at(3, 5)), 1e-4);  // not trivially symmetric: the coefficients are not small
}

// The square's transforms about the window map the coefficients as the Fourier transform says:
// the mirror x -> P - x gives c(-kx, ky); the quarter turn (x, y) -> (P - y, x) gives c(ky, -kx).
// On slanted edges too.
TEST(MaskSpectrum, TransformsOfTheWindow) {
  const std::vector<Polygon> clip{
      Polygon{{{400, 300}, {1000, 650}, {1571, 300}, {1900, 1100}, {1000, 1453}, {613, 1700}, {300, 900}}, {}},
      box(100, 1800, 1500, 1880)};
  auto map = [](std::vector<Polygon> ps, auto f) {
    for (auto& p : ps)
      for (auto& q : p.outer) q = f(q);
    return ps;
  };
  const MaskSpectrum c = spectrum(clip);
  const MaskSpectrum mirrored = spectrum(map(clip, [](Point q) { return Point{2048 - q.x, q.y}; }));
  const MaskSpectrum turned = spectrum(map(clip, [](Point q) { return Point{2048 - q.y, q.x}; }));
  double worst = 0;
  for (int kx = -H; kx <= H; ++kx)
    for (int ky = -H; ky <= H; ++ky) {
      worst = std::max(worst, std::abs(mirrored.at(kx, ky) - c.at(-kx, ky)));
      worst = std::max(worst, std::abs(turned.at(kx, ky) - c.at(ky, -kx)));
    }
  EXPECT_LT(worst, 1e-15);
}

// The window's origin and unit: the same mask 0.1 nm a unit, shifted, has the same spectrum.
TEST(MaskSpectrum, WindowOriginAndUnit) {
  const MaskSpectrum nm = spectrum({box(300, 1000, 460, 1900)});
  const MaskSpectrum dbu({box(-7000 + 3000, 50000 + 10000, -7000 + 4600, 50000 + 19000)}, Window{{-7000, 50000}, 0.1}, P, H);
  EXPECT_LT(max_difference(nm, dbu), 1e-15);
}

TEST(MaskSpectrum, PolygonOutsideTheWindowIsAnError) {
  try {
    MaskSpectrum({box(100, 100, 2049, 300)}, Window{}, P, H);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "mask: the point (2049, 100) lies outside the window of 2048 nm from (0, 0)");
  }
  EXPECT_THROW(MaskSpectrum({box(-1, 0, 10, 10)}, Window{}, P, H), std::invalid_argument);
  EXPECT_THROW(MaskSpectrum({box(0, 0, 10, 10)}, Window{{5, 0}, 1.0}, P, H), std::invalid_argument);
  EXPECT_NO_THROW(MaskSpectrum({box(0, 0, 2048, 2048)}, Window{}, P, H));  // the boundary belongs to the window
}
