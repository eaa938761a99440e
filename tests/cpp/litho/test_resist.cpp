// The threshold resist along measurement lines: printed widths of a line/space grating as the
// line widens (monotonic, pinch below, bridge above), checked against the FFT grid; a neck that
// pinches and a line-end gap that bridges; a gauge's printed CD under the 8 transforms.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include "linf/litho/resist.hpp"
#include "litho/litho_fixtures.hpp"

using namespace linf;
using namespace linf::litho;
using litho_test::box;
using litho_test::focus;
using Outcome = Cut::Outcome;

namespace {

constexpr double P = 2048, T = kIccad13Threshold;

AerialImage image_of(const std::vector<Polygon>& clip) {
  return AerialImage(focus(), MaskSpectrum(clip, Window{}, P, focus().half()));
}

// Vertical lines of width w across the whole window (so, with the period, endless), centred
// on x = pitch / 2 + k pitch.
std::vector<Polygon> grating(int pitch, int w) {
  std::vector<Polygon> lines;
  for (int c = pitch / 2; c < 2048; c += pitch) lines.push_back(box(c - w / 2, 0, c - w / 2 + w, 2048));
  return lines;
}

// The slope of the image along the line at t (central difference of the band-limited image).
double slope(const LineProfile& line, double t) { return (line.at(t + 0.01) - line.at(t - 0.01)) / 0.02; }

}  // namespace

// Pitch 512 nm: the printed width measured along the line's normal grows strictly with the
// drawn width; below ~80 nm the line does not print (pinch), and once the printed width reaches
// the pitch the space prints through (bridge). Where both are measured, line + space = pitch.
TEST(Resist, GratingWidthIsMonotonicWithPinchAndBridge) {
  const int pitch = 512;
  const double centre = 3 * pitch / 2.0;  // the line at x = 768
  std::vector<Outcome> lines, spaces;
  std::vector<double> widths;
  for (int w = 40; w <= 480; w += 8) {
    const AerialImage im = image_of(grating(pitch, w));
    const double x = centre - w / 2 + w / 2.0;  // the drawn line's middle (w odd/even alike)
    const LineProfile across_line(im, x, 1000, 1, 0), across_space(im, x + pitch / 2.0, 1000, -1, 0);
    const Cut line = measure(across_line, T, Across::printed, 600);
    const Cut space = measure(across_space, T, Across::clear, 600);
    lines.push_back(line.outcome);
    spaces.push_back(space.outcome);
    if (line.outcome == Outcome::measured) {
      if (!widths.empty()) EXPECT_GT(line.width, widths.back()) << "w " << w;
      widths.push_back(line.width);
      // An edge is a crossing: the image is at the threshold there, and rising into the line.
      EXPECT_NEAR(across_line.at(line.lo), T, 1e-6);
      EXPECT_NEAR(across_line.at(line.hi), T, 1e-6);
      EXPECT_GT(slope(across_line, line.lo), 0);
      EXPECT_LT(slope(across_line, line.hi), 0);
      ASSERT_EQ(space.outcome, Outcome::measured) << "w " << w;
      EXPECT_NEAR(line.width + space.width, pitch, 1e-5) << "w " << w;
    }
    if (line.outcome == Outcome::pinch) {
      EXPECT_EQ(line.width, 0.0);
      EXPECT_EQ(space.outcome, Outcome::open);  // nothing prints: the space has no edge within 600 nm
    }
    if (space.outcome == Outcome::bridge) {
      EXPECT_EQ(space.width, 0.0);
      EXPECT_EQ(line.outcome, Outcome::open);  // everything prints
    }
  }
  // pinch ... pinch, measured ... measured, bridge ... bridge, each at least twice.
  std::size_t i = 0;
  while (i < lines.size() && lines[i] == Outcome::pinch) ++i;
  const std::size_t pinches = i;
  while (i < lines.size() && lines[i] == Outcome::measured) ++i;
  const std::size_t measured = i - pinches;
  std::size_t bridges = 0;
  for (; i < lines.size(); ++i) bridges += spaces[i] == Outcome::bridge;
  EXPECT_GE(pinches, 2u);
  EXPECT_GE(measured, 20u);
  EXPECT_GE(bridges, 2u);
  EXPECT_EQ(pinches + measured + bridges, lines.size()) << "the outcomes are not in the order pinch, measured, bridge";
  std::printf("[ litho ] pitch 512 grating, drawn 40..480 nm: %zu pinch, %zu measured (printed %.2f .. %.2f nm), %zu bridge\n",
              pinches, measured, widths.front(), widths.back(), bridges);
}

// The root finding against an independent reading: the FFT grid at 4 nm pixels. The printed
// pixels along the row through the line number width / 4 within one pixel on each side.
TEST(Resist, WidthAgreesWithTheGrid) {
  for (int w : {100, 160, 240}) {
    const AerialImage im = image_of(grating(512, w));
    const int m = 512;
    const std::vector<double> g = im.grid(m);
    const int row = 250;  // y = 1000 nm
    int printed = 0;
    for (int i = 512 / 4; i < 1024 / 4; ++i) printed += g[std::size_t(row) * m + std::size_t(i)] >= T;  // x in [512, 1024)
    const Cut cut = measure(LineProfile(im, 768, 1000, 1, 0), T, Across::printed, 300);
    ASSERT_EQ(cut.outcome, Outcome::measured);
    EXPECT_NEAR(cut.width, 4.0 * printed, 8.0) << "w " << w;
    std::printf("[ litho ] drawn %d nm: printed %.3f nm; grid %d pixels of 4 nm\n", w, cut.width, printed);
  }
}

// A wire (120 nm wide, along x) with a neck of width n over 200 nm: measured across the neck,
// the printed width falls with n until the wire breaks there: pinch.
TEST(Resist, NarrowedLinePinches) {
  double last = 1e9;
  bool pinched = false;
  for (int n = 120; n >= 20; n -= 10) {
    const int lo = 1024 - n / 2;
    const std::vector<Polygon> wire{box(300, 964, 924, 1084), box(924, lo, 1124, lo + n), box(1124, 964, 1748, 1084)};
    const Cut cut = measure(LineProfile(image_of(wire), 1024, lo + n / 2.0, 0, 1), T, Across::printed, 400);
    if (pinched) {
      EXPECT_EQ(cut.outcome, Outcome::pinch) << "a neck of " << n << " nm prints after a wider one pinched";
      continue;
    }
    if (cut.outcome == Outcome::pinch) {
      pinched = true;
      std::printf("[ litho ] neck of a 120 nm wire over 200 nm: pinches at %d nm (printed %.2f nm at %d)\n", n, last, n + 10);
      continue;
    }
    ASSERT_EQ(cut.outcome, Outcome::measured) << n;
    EXPECT_LT(cut.width, last) << n;
    last = cut.width;
  }
  EXPECT_TRUE(pinched);
}

// Two wire ends facing across a gap g: measured along the wires through the gap's middle, the
// printed gap shrinks with g until the ends print into each other: bridge.
TEST(Resist, ClosedGapBridges) {
  double last = 1e9;
  bool bridged = false;
  for (int g = 200; g >= 10; g -= 10) {
    const int a = 1024 - g / 2;
    const std::vector<Polygon> ends{box(300, 964, a, 1084), box(a + g, 964, 1748, 1084)};
    const Cut cut = measure(LineProfile(image_of(ends), a + g / 2.0, 1024, 1, 0), T, Across::clear, 400);
    if (bridged) {
      EXPECT_EQ(cut.outcome, Outcome::bridge) << g;
      continue;
    }
    if (cut.outcome == Outcome::bridge) {
      bridged = true;
      std::printf("[ litho ] line-end gap of 120 nm wires: bridges at %d nm (printed gap %.2f nm at %d)\n", g, last, g + 10);
      continue;
    }
    ASSERT_EQ(cut.outcome, Outcome::measured) << g;
    EXPECT_LT(cut.width, last) << g;
    last = cut.width;
  }
  EXPECT_TRUE(bridged);
}

// A gauge's printed CD is the same under the 8 transforms of its clip, to the image's symmetry
// bound (test_image.cpp) divided by the image's slope at the two edges.
TEST(Resist, PrintedWidthUnderTheSquaresTransforms) {
  const std::vector<Polygon> clip{box(700, 600, 790, 1450), box(880, 600, 970, 1200),
                                  Polygon{{{1060, 700}, {1400, 700}, {1400, 790}, {1150, 790}, {1150, 1300}, {1060, 1300}}, {}},
                                  box(1250, 900, 1350, 1000)};
  const MaskSpectrum spectrum(clip, Window{}, P, focus().half());
  double energy = 0;
  for (int kx = -17; kx <= 17; ++kx)
    for (int ky = -17; ky <= 17; ++ky) energy += std::norm(spectrum.at(kx, ky));
  const double image_bound = litho_test::tcc_symmetry_defect(focus()) * energy;
  // Gauges: across the first line (x), across the L's foot (y), across the space between lines.
  struct Gauge {
    double x, y, dx, dy;
    Across what;
  };
  const std::vector<Gauge> gauges{{745, 1000, 1, 0, Across::printed}, {1250, 745, 0, 1, Across::printed},
                                  {835, 900, 1, 0, Across::clear}};
  double worst = 0, allowed = 1e300;
  const AerialImage im = image_of(clip);
  for (const Gauge& gauge : gauges) {
    const LineProfile base(im, gauge.x, gauge.y, gauge.dx, gauge.dy);
    const Cut want = measure(base, T, gauge.what, 400);
    ASSERT_EQ(want.outcome, Outcome::measured);
    const double tol = image_bound / std::abs(slope(base, want.lo)) + image_bound / std::abs(slope(base, want.hi));
    allowed = std::min(allowed, tol);
    for (int swap = 0; swap < 2; ++swap)
      for (int sx = -1; sx <= 1; sx += 2)
        for (int sy = -1; sy <= 1; sy += 2) {
          auto gx = [&](double x, double y) { return 1024 + sx * ((swap ? y : x) - 1024); };
          auto gy = [&](double x, double y) { return 1024 + sy * ((swap ? x : y) - 1024); };
          std::vector<Polygon> moved = clip;
          for (auto& p : moved)
            for (auto& q : p.outer) q = Point{Coord(gx(double(q.x), double(q.y))), Coord(gy(double(q.x), double(q.y)))};
          const double dx = sx * (swap ? gauge.dy : gauge.dx), dy = sy * (swap ? gauge.dx : gauge.dy);
          const AerialImage other = image_of(moved);
          const Cut got = measure(LineProfile(other, gx(gauge.x, gauge.y), gy(gauge.x, gauge.y), dx, dy), T, gauge.what, 400);
          ASSERT_EQ(got.outcome, Outcome::measured);
          EXPECT_NEAR(got.width, want.width, tol);
          worst = std::max(worst, std::abs(got.width - want.width));
        }
  }
  std::printf("[ litho ] printed CD under the 8 transforms: max difference %.3g nm (allowed %.3g nm)\n", worst, allowed);
}

TEST(Resist, BadInputAndOpenEnds) {
  const AerialImage im = image_of(grating(512, 200));
  const LineProfile line(im, 256, 1000, 1, 0);
  EXPECT_THROW(measure(line, T, Across::printed, 100, 0), std::invalid_argument);
  EXPECT_THROW(measure(line, T, Across::printed, 0), std::invalid_argument);
  // A reach shorter than half the printed line: no edge within it on either side.
  const Cut near = measure(line, T, Across::printed, 50);
  EXPECT_EQ(near.outcome, Outcome::open);
  EXPECT_EQ(near.lo, -50.0);
  EXPECT_EQ(near.hi, 50.0);
}
