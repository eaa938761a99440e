// The aerial image: a clear field, an empty mask, the grid against the point evaluation, line
// profiles, the square's 8 transforms, bad input, and the time a window takes (printed).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <vector>

#include "linf/litho/image.hpp"
#include "litho/litho_fixtures.hpp"

using namespace linf;
using namespace linf::litho;
using litho_test::box;
using litho_test::focus;

namespace {

constexpr double P = 2048;

AerialImage image_of(const std::vector<Polygon>& clip) {
  return AerialImage(focus(), MaskSpectrum(clip, Window{}, P, focus().half()));
}

// A metal-1-like clip, deliberately without symmetry: lines, an L, a T, a jog, an island and
// a slanted piece, around the window's centre.
std::vector<Polygon> clip() {
  return {box(700, 600, 790, 1450),
          box(880, 600, 970, 1200),
          Polygon{{{1060, 700}, {1400, 700}, {1400, 790}, {1150, 790}, {1150, 1300}, {1060, 1300}}, {}},
          Polygon{{{880, 1300}, {1350, 1300}, {1350, 1390}, {1160, 1390}, {1160, 1500}, {1070, 1500}, {1070, 1390}, {880, 1390}}, {}},
          box(1250, 900, 1350, 1000),
          Polygon{{{600, 1550}, {1000, 1550}, {1100, 1650}, {700, 1650}}, {}}};
}

// The 8 transforms of the square about the window's centre, g(x, y) = C + R (p - C).
struct Transform {
  bool swap;
  int sx, sy;
  double x(double px, double py) const { return 1024 + sx * ((swap ? py : px) - 1024); }
  double y(double px, double py) const { return 1024 + sy * ((swap ? px : py) - 1024); }
  Point operator()(Point p) const { return {Coord(x(double(p.x), double(p.y))), Coord(y(double(p.x), double(p.y)))}; }
};

std::vector<Transform> transforms() {
  std::vector<Transform> t;
  for (int swap = 0; swap < 2; ++swap)
    for (int sx = -1; sx <= 1; sx += 2)
      for (int sy = -1; sy <= 1; sy += 2) t.push_back({swap == 1, sx, sy});
  return t;
}

}  // namespace

// A clear field (the whole window open) images to the constant sum_i w_i |K_i(0,0)|^2, which
// is 0.953645 for iccad13 (a model normalised to a clear field of 1 would give 1).
TEST(AerialImage, ClearFieldImagesToAConstant) {
  const AerialImage im = image_of({box(0, 0, 2048, 2048)});
  const double want = focus().clear_field();
  EXPECT_NEAR(want, 0.953645, 1e-6);
  for (double v : im.grid(64)) ASSERT_NEAR(v, want, 1e-12);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-3000, 5000);
  for (int i = 0; i < 100; ++i) ASSERT_NEAR(im.at(u(rng), u(rng)), want, 1e-12);
}

TEST(AerialImage, EmptyMaskImagesToZero) {
  const AerialImage im = image_of({});
  for (double v : im.grid(64)) ASSERT_EQ(v, 0.0);
  EXPECT_EQ(im.at(1024, 1024), 0.0);
  EXPECT_EQ(LineProfile(im, 10, 20, 1, 0).at(5), 0.0);
}

// The FFT grid and the band-limited sum read the same spectra: every pixel of a 128 x 128 grid
// (16 nm) equals the point evaluation there, to rounding; one thread and two give the same.
TEST(AerialImage, GridAndPointsAgree) {
  const AerialImage im = image_of(clip());
  const int m = 128;
  const std::vector<double> g1 = im.grid(m, 1), g2 = im.grid(m, 2);
  double worst = 0, top = 0, threads = 0;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) {
      const double v = g1[std::size_t(j) * m + std::size_t(i)];
      worst = std::max(worst, std::abs(v - im.at(i * P / m, j * P / m)));
      threads = std::max(threads, std::abs(v - g2[std::size_t(j) * m + std::size_t(i)]));
      top = std::max(top, v);
    }
  std::printf("[ litho ] grid 128 vs points: max |difference| %.3g (image max %.3f)\n", worst, top);
  EXPECT_GT(top, 0.5);  // the clip prints
  EXPECT_LT(worst, 1e-12);
  EXPECT_LT(threads, 1e-12);
  // A finer grid holds the coarser one's pixels.
  const std::vector<double> g4 = im.grid(4 * m);
  for (int j = 0; j < m; j += 7)
    for (int i = 0; i < m; i += 5)
      EXPECT_NEAR(g4[std::size_t(4 * j) * 4 * m + std::size_t(4 * i)], g1[std::size_t(j) * m + std::size_t(i)], 1e-12);
}

// A line profile reads the same image: along x, along -y (the 1-D reduction) and slanted (the
// 2-D sum), at real t, against the point evaluation.
TEST(AerialImage, LineProfilesAgreeWithPoints) {
  const AerialImage im = image_of(clip());
  struct Line {
    double px, py, dx, dy;
  };
  for (const Line& l : {Line{745, 1000, 1, 0}, Line{925.5, 980.25, 0, -1}, Line{1000, 1000, 3, 4}}) {
    const LineProfile profile(im, l.px, l.py, l.dx, l.dy);
    const double len = std::hypot(l.dx, l.dy);
    for (double t = -300; t <= 300; t += 7.3)
      ASSERT_NEAR(profile.at(t), im.at(l.px + t * l.dx / len, l.py + t * l.dy / len), 1e-12) << t;
  }
  EXPECT_THROW(LineProfile(im, 0, 0, 0, 0), std::invalid_argument);
}

// The profile formed straight from the kernels and the mask (what printability reads, without
// the image's fields) is the image's: along both axes both ways, at half-unit points, and
// slanted (where it images the window itself), with a mask of more frequencies than the kernels;
// with an even and an odd number of kernels (the profiles take them two at a time).
TEST(AerialImage, ProfilesFromKernelsAndMaskAreTheImages) {
  Kernels odd = focus();
  odd.weights.pop_back();
  odd.values.pop_back();
  ASSERT_EQ(odd.count() % 2, 1u);
  for (const Kernels* kernels : {&focus(), static_cast<const Kernels*>(&odd)}) {
    const MaskSpectrum mask(clip(), Window{}, P, kernels->half() + 3);
    const AerialImage im(*kernels, mask);
    struct Line {
      double px, py, dx, dy;
    };
    double scale = 0;
    for (double t = -300; t <= 300; t += 50) scale = std::max(scale, im.at(1000 + t, 1000));
    ASSERT_GT(scale, 0.1);
    for (const Line& l : {Line{745, 1000, 1, 0}, Line{925.5, 980.25, 0, -1}, Line{1111, 777.5, -2, 0},
                          Line{830, 1222, 0, 5}, Line{1000, 1000, 3, 4}}) {
      const LineProfile direct(LineKernels(*kernels), mask, l.px, l.py, l.dx, l.dy), via(im, l.px, l.py, l.dx, l.dy);
      const double len = std::hypot(l.dx, l.dy);
      for (double t = -300; t <= 300; t += 3.7) {
        const double want = im.at(l.px + t * l.dx / len, l.py + t * l.dy / len);
        ASSERT_NEAR(direct.at(t), want, 1e-12 * scale) << l.px << " " << l.py << " " << t;
        ASSERT_NEAR(via.at(t), want, 1e-12 * scale) << l.px << " " << l.py << " " << t;
      }
    }
  }
  const MaskSpectrum mask(clip(), Window{}, P, focus().half() + 3);
  const LineKernels lk(focus());
  EXPECT_THROW(LineProfile(lk, mask, 0, 0, 0, 0), std::invalid_argument);
  EXPECT_THROW(LineProfile(lk, MaskSpectrum({}, Window{}, P, 10), 0, 0, 1, 0), std::invalid_argument);
  EXPECT_THROW(LineProfile(lk, MaskSpectrum({}, Window{}, 1024, 17), 0, 0, 1, 0), std::invalid_argument);
  EXPECT_THROW(LineKernels(Kernels{}), std::invalid_argument);
}

// Profiles made together (LineProfile::batch: 8 lines to a group, so 19 lines make full and
// partial groups along each axis) are the same bits as each made alone: along both axes,
// slanted, in windows of different masks, in any order.
TEST(AerialImage, ProfilesMadeTogetherAreTheProfilesMadeAlone) {
  const LineKernels lk(focus());
  std::vector<MaskSpectrum> masks;
  for (int k = 0; k < 3; ++k) {
    std::vector<Polygon> c = clip();
    c.push_back(box(200 + 100 * k, 300, 260 + 100 * k, 1700));  // a different mask each
    masks.emplace_back(c, Window{}, P, focus().half());
  }
  std::vector<Probe> probes;
  for (int j = 0; j < 19; ++j) {
    const double dx = j % 5 == 4 ? 3 : j % 2 == 0 ? (j % 4 == 0 ? 1 : -2) : 0;
    const double dy = j % 5 == 4 ? 4 : j % 2 == 1 ? (j % 3 == 0 ? -1 : 5) : 0;
    probes.push_back({&masks[std::size_t(j % 3)], 700 + 31.5 * j, 1300 - 27.25 * j, dx, dy});
  }
  const std::vector<LineProfile> together = LineProfile::batch(lk, probes);
  ASSERT_EQ(together.size(), probes.size());
  for (std::size_t j = 0; j < probes.size(); ++j) {
    const Probe& p = probes[j];
    const LineProfile alone(lk, *p.mask, p.px, p.py, p.dx, p.dy);
    for (double t = -200; t <= 200; t += 6.1) ASSERT_EQ(together[j].at(t), alone.at(t)) << j << " " << t;
  }
  // Two kernel sets (a model's focus and defocused ones) share the masks' layout: each set's
  // profiles are its own batch's; sets of another size are refused.
  Kernels scaled = focus();
  for (auto& v : scaled.values)
    for (auto& x : v) x *= std::complex<double>(0.6, 0.8);  // a phase: the same image, other fields
  const LineKernels lk2(scaled);
  const std::vector<std::vector<LineProfile>> both = LineProfile::batch({&lk, &lk2}, probes);
  const std::vector<LineProfile> second = LineProfile::batch(lk2, probes);
  ASSERT_EQ(both.size(), 2u);
  for (std::size_t j = 0; j < probes.size(); ++j)
    for (double t = -200; t <= 200; t += 17.3) {
      ASSERT_EQ(both[0][j].at(t), together[j].at(t)) << j << " " << t;
      ASSERT_EQ(both[1][j].at(t), second[j].at(t)) << j << " " << t;
    }
  Kernels small = focus();
  small.size -= 2;
  for (auto& v : small.values) v.resize(std::size_t(small.size) * std::size_t(small.size));
  const LineKernels lk3(small);
  EXPECT_THROW(LineProfile::batch({&lk, &lk3}, probes), std::invalid_argument);
  EXPECT_TRUE(LineProfile::batch(lk, {}).empty());
  EXPECT_THROW(LineProfile::batch(lk, {probes[0], Probe{&masks[0], 0, 0, 0, 0}}), std::invalid_argument);
}

// The resist's blur along a line is the unblurred profile convolved with the Gaussian (summed
// here by the trapezoid rule over +-8 sigma, spectrally exact for this band-limited image):
// along both axes (the polynomial's exact factor) and slanted (the image's spectrum from a grid).
// A grid blurred in 2-D agrees with a line's blur where the image does not change across the
// line (endless lines); sigma 0 changes nothing; a negative sigma is refused.
TEST(AerialImage, BlurIsTheGaussianConvolution) {
  const AerialImage im = image_of(clip());
  struct Line {
    double px, py, dx, dy;
  };
  for (const double sigma : {5.0, 20.0})
    for (const Line& l : {Line{745, 1000, 1, 0}, Line{925.5, 980.25, 0, -1}, Line{1000, 1000, 3, 4}}) {
      const LineProfile bare(im, l.px, l.py, l.dx, l.dy);
      LineProfile blurred(im, l.px, l.py, l.dx, l.dy);
      blurred.blur(sigma);
      const double h = sigma / 8;
      double scale = 0;
      for (double t = -150; t <= 150; t += 10) scale = std::max(scale, bare.at(t));
      for (double t = -150; t <= 150; t += 9.7) {
        double sum = 0, weights = 0;
        for (int k = -64; k <= 64; ++k) {
          const double u = k * h, w = std::exp(-0.5 * u * u / (sigma * sigma));
          sum += w * bare.at(t - u);
          weights += w;
        }
        ASSERT_NEAR(blurred.at(t), sum / weights, 1e-9 * scale) << sigma << " " << l.dx << " " << l.dy << " " << t;
      }
    }
  // Endless vertical lines: the image is the same along y, so the 2-D blur is the 1-D one.
  std::vector<Polygon> lines;
  for (Coord c = 100; c < 2048; c += 256) lines.push_back(box(c, 0, c + 100, 2048));
  const AerialImage grating(focus(), MaskSpectrum(lines, Window{}, P, focus().half()));
  const int m = 128;
  std::vector<double> grid = grating.grid(m);
  blur_grid(grid, m, P, 30);
  LineProfile row(grating, 0, 37 * P / m, 1, 0);
  row.blur(30);
  for (int i = 0; i < m; i += 5) ASSERT_NEAR(grid[std::size_t(37 * m + i)], row.at(i * P / m), 1e-12) << i;
  std::vector<double> same = grating.grid(m);
  const std::vector<double> before = same;
  blur_grid(same, m, P, 0);
  EXPECT_EQ(same, before);
  LineProfile line(im, 745, 1000, 1, 0);
  EXPECT_THROW(line.blur(-1), std::invalid_argument);
  EXPECT_THROW(blur_grid(same, m, P, -1), std::invalid_argument);
}

// The image of a clip equals the transformed image of each of its 8 transforms at matching
// points. The tolerance is not a guess: for any mask, |I'(g(q)) - I(q)| <= ||T o g - T|| sum |c|^2
// (the TCC's symmetry defect, measured from the kernels, times the mask's spectral energy);
// with float32 kernels and 24 of them, that is what the model itself guarantees.
TEST(AerialImage, SymmetricUnderTheSquaresTransforms) {
  const AerialImage im = image_of(clip());
  const MaskSpectrum spectrum(clip(), Window{}, P, focus().half());
  double energy = 0;
  for (int kx = -17; kx <= 17; ++kx)
    for (int ky = -17; ky <= 17; ++ky) energy += std::norm(spectrum.at(kx, ky));
  const double bound = litho_test::tcc_symmetry_defect(focus()) * energy + 1e-12;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(500, 1600);
  std::vector<std::pair<double, double>> points;
  for (int i = 0; i < 300; ++i) points.push_back({u(rng), u(rng)});
  double worst = 0, worst_transform_identity = 0;
  for (const Transform& g : transforms()) {
    std::vector<Polygon> moved = clip();
    for (auto& p : moved)
      for (auto& q : p.outer) q = g(q);
    const AerialImage other = image_of(moved);
    for (auto [x, y] : points) {
      const double d = std::abs(other.at(g.x(x, y), g.y(x, y)) - im.at(x, y));
      worst = std::max(worst, d);
      if (!g.swap && g.sx == 1 && g.sy == 1) worst_transform_identity = std::max(worst_transform_identity, d);
    }
  }
  std::printf("[ litho ] symmetry: max |I'(g q) - I(q)| over 8 transforms %.3g; bound %.3g\n", worst, bound);
  EXPECT_LT(worst_transform_identity, 1e-15);  // the identity (its points rounded once)
  EXPECT_LE(worst, bound);
  EXPECT_GT(worst, 0.0);  // the transforms were really applied (the clip has no symmetry)
}

TEST(AerialImage, BadInput) {
  EXPECT_THROW(AerialImage(focus(), MaskSpectrum({}, Window{}, 1024, 17)), std::invalid_argument);  // another period
  EXPECT_THROW(AerialImage(focus(), MaskSpectrum({}, Window{}, P, 10)), std::invalid_argument);     // too few frequencies
  EXPECT_THROW(image_of({}).grid(34), std::invalid_argument);                                           // < 35 pixels a side
  EXPECT_THROW(AerialImage(Kernels{}, MaskSpectrum({}, Window{}, P, 17)), std::invalid_argument);    // no kernels
}

// Figures for docs/design.md, printed, not asserted: one 2048 nm window at M = 256 (8 nm
// pixels) with the 24 kernels, on a window of ~300 rectangles.
TEST(AerialImage, TimePerWindow) {
  std::vector<Polygon> dense;
  for (int c = 0; c < 2048 - 64; c += 128)
    for (int r = 0; r < 2048 - 64; r += 96) dense.push_back(box(c + 16, r + 8, c + 16 + 64 + (r % 3) * 8, r + 8 + 48));
  using clock = std::chrono::steady_clock;
  auto ms = [](clock::time_point a, clock::time_point b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
  const auto t0 = clock::now();
  const MaskSpectrum spectrum(dense, Window{}, P, focus().half());
  const auto t1 = clock::now();
  const AerialImage im(focus(), spectrum);
  const auto t2 = clock::now();
  double sink = im.grid(256, 1)[0];  // the first grid of a size makes FFTW's plans
  const auto t2b = clock::now();
  for (int rep = 0; rep < 5; ++rep) sink += im.grid(256, 1)[0];
  const auto t3 = clock::now();
  for (int rep = 0; rep < 5; ++rep) sink += im.grid(256, 2)[0];
  const auto t4 = clock::now();
  for (int i = 0; i < 1000; ++i) sink += im.at(i, 2 * i);
  const auto t5 = clock::now();
  const LineProfile line(im, 1000, 1000, 1, 0);
  const auto t6 = clock::now();
  for (int i = 0; i < 1000; ++i) sink += line.at(i * 0.1);
  const auto t7 = clock::now();
  std::printf("[ litho ] window of %zu rectangles: spectrum %.2f ms, fields %.2f ms, first grid 256 x 256 (with "
              "planning) %.1f ms, then %.1f ms (1 thread) %.1f ms (2 threads), point %.1f us, line setup %.1f us, "
              "line point %.2f us (%g)\n",
              dense.size(), ms(t0, t1), ms(t1, t2), ms(t2, t2b), ms(t2b, t3) / 5, ms(t3, t4) / 5, ms(t4, t5),
              ms(t5, t6) * 1000, ms(t6, t7), sink > 0 ? 1.0 : 0.0);
  EXPECT_GT(sink, 0);
}
