// Kernels from optics: a clear field images to 1; coherent imaging of a grating gives the image
// theory predicts (contrast, defocus); SOCS agrees with a direct Abbe sum over the source;
// defocus is symmetric; the kernel set keeps the source's symmetry; bad optics are errors.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "linf/litho/optics.hpp"
#include "linf/litho/image.hpp"
#include "litho/litho_fixtures.hpp"

using namespace linf;
using namespace linf::litho;
using litho_test::box;
using cd = std::complex<double>;

namespace {

const double kPi = std::acos(-1.0);

std::vector<Polygon> grating(int period, int pitch, int w) {
  std::vector<Polygon> lines;
  for (int c = pitch / 2; c < period; c += pitch) lines.push_back(box(c - w / 2, 0, c - w / 2 + w, period));
  return lines;
}

AerialImage image_of(const Kernels& k, const std::vector<Polygon>& clip) {
  return AerialImage(k, MaskSpectrum(clip, Window{}, k.period, k.half()));
}

Optics coherent() {
  Optics o = optics_preset("duv193");
  o.sigma_in = o.sigma_out = 0;
  return o;
}

std::string error_of(const Optics& o) {
  try {
    kernels_from_optics(o);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(Optics, PresetsAndClearFieldIsOne) {
  const Optics duv = optics_preset("duv193"), euv = optics_preset("euv");
  EXPECT_EQ(duv.wavelength, 193.0);
  EXPECT_EQ(duv.na, 1.35);
  EXPECT_EQ(duv.medium, 1.44);
  EXPECT_EQ(duv.sigma_in, 0.7);
  EXPECT_EQ(duv.sigma_out, 0.9);
  EXPECT_EQ(duv.period, 2048.0);
  EXPECT_EQ(euv.wavelength, 13.5);
  EXPECT_EQ(euv.na, 0.33);
  EXPECT_EQ(euv.medium, 1.0);
  EXPECT_EQ(euv.sigma_in, 0.5);
  EXPECT_EQ(euv.sigma_out, 0.9);
  EXPECT_EQ(euv.period, 512.0);
  for (const Optics& o : {duv, euv}) {
    const Kernels k = kernels_from_optics(o);
    EXPECT_EQ(k.count(), 24u);
    EXPECT_NEAR(k.clear_field(), 1.0, 1e-12);
    const Coord p = Coord(o.period);
    for (double v : image_of(k, {box(0, 0, p, p)}).grid(64)) ASSERT_NEAR(v, 1.0, 1e-12);
    for (std::size_t i = 0; i < k.count(); ++i) {
      double norm2 = 0;
      for (const cd& v : k.values[i]) norm2 += std::norm(v);
      EXPECT_NEAR(norm2, 1.0, 1e-9) << i;
      if (i > 0) EXPECT_LE(k.weights[i], k.weights[i - 1] * (1 + 1e-12));
    }
  }
}

// Coherent light (sigma 0), a grating of pitch 256 nm and lines of 100 nm at 193 nm / NA 1.35:
// orders 0 and +-1 pass (1/256 < NA/lambda = 1/143), +-2 and beyond do not (2/256 > 1/143), so
// the field is E(x) = c0 + 2 c1 cos(2 pi (x - xc) / p), c0 = w/p, c1 = sin(pi w/p)/pi, and
// I = E^2: contrast 4 c0 c1 / (c0^2 + 4 c1^2). Defocused by z, the first orders turn by
// phi = 2 pi z (sqrt(n^2/lambda^2 - 1/p^2) - n/lambda): I = c0^2 + 4 c1^2 cos^2 + 4 c0 c1 cos cos(phi).
TEST(Optics, CoherentGratingGivesTheTheorysImage) {
  const int pitch = 256, w = 100;
  const double c0 = double(w) / pitch, c1 = std::sin(kPi * w / pitch) / kPi;
  for (const double z : {0.0, 80.0}) {
    Optics o = coherent();
    o.defocus = z;
    const Kernels k = kernels_from_optics(o);
    ASSERT_EQ(k.count(), 1u);
    const AerialImage im = image_of(k, grating(2048, pitch, w));
    const double n = o.medium / o.wavelength, phi = 2 * kPi * z * (std::sqrt(n * n - 1.0 / (pitch * pitch)) - n);
    const double xc = 3 * pitch / 2.0 - w / 2 + w / 2.0;
    double worst = 0;
    for (double x = xc - pitch; x <= xc + pitch; x += 3.7) {
      const double cs = std::cos(2 * kPi * (x - xc) / pitch);
      const double want = c0 * c0 + 4 * c1 * c1 * cs * cs + 4 * c0 * c1 * cs * std::cos(phi);
      worst = std::max(worst, std::abs(im.at(x, 321.5) - want));
    }
    EXPECT_LT(worst, 1e-12) << "defocus " << z;
    const double imax = im.at(xc, 0), imin = im.at(xc + pitch / 2.0, 0);
    const double contrast = (imax - imin) / (imax + imin);
    const double theory = z == 0 ? 4 * c0 * c1 / (c0 * c0 + 4 * c1 * c1)
                                 : 4 * c0 * c1 * std::cos(phi) / (c0 * c0 + 4 * c1 * c1);
    EXPECT_NEAR(contrast, theory, 1e-12) << "defocus " << z;
    std::printf("[ litho ] coherent grating 100/256 nm, defocus %g nm: contrast %.6f (theory %.6f)\n", z, contrast, theory);
  }
}

// SOCS against a direct Abbe sum: for each source point s (the same sampling), the coherent
// image |sum_k c(k) P(k + s) e^{2 pi i k.x / P}|^2, averaged over the source. With every kernel
// kept the two are the same model computed two ways; with 24 kept, they differ by at most the
// first weight left out times the mask's spectral energy, plus the clear-field rescaling.
TEST(Optics, SocsAgreesWithAnAbbeSum) {
  Optics o = optics_preset("duv193");
  o.period = 1024;  // small: n = 27, 100 source points
  o.defocus = 40;
  const std::vector<Polygon> clip{box(300, 350, 390, 700), box(460, 350, 550, 600),
                                  Polygon{{{600, 300}, {760, 300}, {760, 380}, {680, 380}, {680, 700}, {600, 700}}, {}}};
  const MaskSpectrum c(clip, Window{}, o.period, 40);
  // The Abbe sum, written out on its own.
  const double r = o.na * o.period / o.wavelength, kn = o.medium / o.wavelength;
  std::vector<std::pair<int, int>> src;
  for (int jx = -20; jx <= 20; ++jx)
    for (int jy = -20; jy <= 20; ++jy) {
      const double d = std::hypot(double(jx), double(jy));
      if (d <= o.sigma_out * r + 1e-9 && d >= o.sigma_in * r - 1e-9) src.push_back({jx, jy});
    }
  auto abbe = [&](double x, double y) {
    double sum = 0;
    for (auto [jx, jy] : src) {
      cd e = 0;
      for (int kx = -40; kx <= 40; ++kx)
        for (int ky = -40; ky <= 40; ++ky) {
          const double fx = kx + jx, fy = ky + jy, f2 = fx * fx + fy * fy;
          if (f2 > r * r * (1 + 1e-9)) continue;
          const double pupil_phase = 2 * kPi * o.defocus * (std::sqrt(kn * kn - f2 / (o.period * o.period)) - kn);
          e += c.at(kx, ky) * std::polar(1.0, pupil_phase + 2 * kPi * (kx * x + ky * y) / o.period);
        }
      sum += std::norm(e);
    }
    return sum / double(src.size());
  };
  Optics all = o;
  all.kernels = 100000;
  const Kernels every = kernels_from_optics(all), some = kernels_from_optics(o);
  ASSERT_GT(every.count(), some.count());
  const AerialImage full = image_of(every, clip), truncated = image_of(some, clip);
  double energy = 0;
  for (int kx = -some.half(); kx <= some.half(); ++kx)
    for (int ky = -some.half(); ky <= some.half(); ++ky) energy += std::norm(c.at(kx, ky));
  double clear_kept = 0;  // the clear field of the kept kernels before rescaling
  for (std::size_t i = 0; i < some.count(); ++i) clear_kept += every.weights[i] * std::norm(every.at(i, 0, 0));
  double worst_full = 0, worst_kept = 0, top = 0;
  std::vector<double> abbe_values;
  for (double x = 250; x <= 800; x += 55)
    for (double y = 300; y <= 750; y += 75) {
      const double want = abbe(x, y);
      top = std::max(top, want);
      worst_full = std::max(worst_full, std::abs(full.at(x, y) - want));
      worst_kept = std::max(worst_kept, std::abs(truncated.at(x, y) - want));
    }
  const double bound = every.weights[some.count()] * energy / clear_kept + top * std::abs(1 / clear_kept - 1);
  std::printf("[ litho ] SOCS vs Abbe (%zu source points): all %zu kernels %.3g, 24 kernels %.3g (bound %.3g), image max %.3f\n",
              src.size(), every.count(), worst_full, worst_kept, bound, top);
  EXPECT_GT(top, 0.3);
  EXPECT_LT(worst_full, 1e-10);
  EXPECT_LE(worst_kept, bound);
}

// An unaberrated image is the same at +z and -z (a real mask, a point-symmetric source), and
// a grating's contrast falls with defocus.
TEST(Optics, DefocusIsSymmetricAndBlurs) {
  Optics o = optics_preset("duv193");
  o.period = 1024;
  const std::vector<Polygon> lines = grating(1024, 128, 64);
  double contrast[3];
  const double zs[3] = {0, 100, -100};
  std::vector<double> at_plus, at_minus;
  for (int i = 0; i < 3; ++i) {
    o.defocus = zs[i];
    const AerialImage im = image_of(kernels_from_optics(o), lines);
    const double imax = im.at(64 * 3, 10), imin = im.at(64 * 4, 10);
    contrast[i] = (imax - imin) / (imax + imin);
    for (double x = 0; x < 256; x += 9.5) (i == 1 ? at_plus : at_minus).push_back(im.at(x, 10));
  }
  for (std::size_t j = 0; j < at_plus.size(); ++j) EXPECT_NEAR(at_plus[j], at_minus[j + at_plus.size()], 1e-12);
  std::printf("[ litho ] duv193 grating 64/128 nm: contrast %.4f in focus, %.4f at 100 nm defocus\n", contrast[0], contrast[1]);
  EXPECT_LT(contrast[1], 0.9 * contrast[0]);
  EXPECT_NEAR(contrast[1], contrast[2], 1e-12);
}

// The kernels keep the square's symmetry of the annular source: a group of equal weights (x-
// and y-like kernels) is never split, so the TCC of the kept set maps onto itself.
TEST(Optics, KernelSetKeepsTheSourcesSymmetry) {
  Optics o = optics_preset("duv193");
  o.period = 1024;
  for (int asked : {24, 2, 3}) {
    o.kernels = asked;
    const Kernels k = kernels_from_optics(o);
    double norm = 0;
    for (double w : k.weights) norm += w * w;
    EXPECT_LT(litho_test::tcc_symmetry_defect(k), 1e-9 * std::sqrt(norm)) << asked << " kernels asked, " << k.count() << " kept";
    if (asked == 2) EXPECT_EQ(k.count(), 1u);  // the second and third weights are a pair
    if (asked == 3) EXPECT_EQ(k.count(), 3u);
  }
}

// Quasar: four poles on the diagonals. The set keeps the square's symmetry, a clear field is 1,
// an opening of 90 degrees is the whole ring, and poles of 30 degrees image otherwise.
TEST(Optics, QuasarPoles) {
  Optics ring = optics_preset("duv193");
  ring.period = 1024;
  Optics quasar = ring, whole = ring;
  quasar.quasar_opening = 30;
  whole.quasar_opening = 90;
  const Kernels kq = kernels_from_optics(quasar);
  double norm = 0;
  for (double w : kq.weights) norm += w * w;
  EXPECT_NEAR(kq.clear_field(), 1.0, 1e-12);
  EXPECT_LT(litho_test::tcc_symmetry_defect(kq), 1e-9 * std::sqrt(norm));
  const std::vector<Polygon> clip{box(300, 350, 390, 700), box(460, 350, 550, 600), box(600, 300, 700, 380)};
  const AerialImage a = image_of(kernels_from_optics(ring), clip), w = image_of(kernels_from_optics(whole), clip),
                    q = image_of(kq, clip);
  double same = 0, differ = 0;
  for (double x = 250; x <= 800; x += 25)
    for (double y = 300; y <= 750; y += 25) {
      same = std::max(same, std::abs(a.at(x, y) - w.at(x, y)));
      differ = std::max(differ, std::abs(a.at(x, y) - q.at(x, y)));
    }
  EXPECT_LT(same, 1e-12);
  EXPECT_GT(differ, 1e-2);
  std::printf("[ litho ] quasar 30 degrees against annular 0.7 / 0.9: max image difference %.3f\n", differ);
}

TEST(Optics, BadOpticsGiveAClearError) {
  Optics o = optics_preset("duv193");
  o.medium = 1;
  EXPECT_EQ(error_of(o), "optics: a numerical aperture of 1.35 needs immersion: it must be below the medium's index (1, dry)");
  o = optics_preset("euv");
  o.na = 1.0;
  EXPECT_EQ(error_of(o), "optics: a numerical aperture of 1 needs immersion: it must be below the medium's index (1, dry)");
  o = optics_preset("duv193");
  o.sigma_in = -0.1;
  EXPECT_EQ(error_of(o), "optics: sigma must not be negative");
  o = optics_preset("duv193");
  o.sigma_in = 0.95;
  EXPECT_EQ(error_of(o), "optics: the inner sigma must not exceed the outer sigma");
  o.sigma_out = 1.2;
  EXPECT_EQ(error_of(o), "optics: the outer sigma must not exceed 1 (the source must fit in the pupil)");
  o = optics_preset("duv193");
  o.wavelength = 0;
  EXPECT_EQ(error_of(o), "optics: the wavelength must be positive");
  o = optics_preset("duv193");
  o.na = -1;
  EXPECT_EQ(error_of(o), "optics: the numerical aperture must be positive");
  o = optics_preset("duv193");
  o.quasar_opening = 100;
  EXPECT_EQ(error_of(o), "optics: the quasar opening must be between 0 and 90 degrees");
  o.quasar_opening = -5;
  EXPECT_EQ(error_of(o), "optics: the quasar opening must be between 0 and 90 degrees");
  o = optics_preset("duv193");
  o.kernels = 0;
  EXPECT_EQ(error_of(o), "optics: at least one kernel is needed");
  o = optics_preset("duv193");
  o.sigma_in = 0.70;
  o.sigma_out = 0.701;  // a ring thinner than the source's sampling step (0.07)
  EXPECT_NE(error_of(o).find("optics: no source point between sigma 0.7 and 0.701"), std::string::npos) << error_of(o);
  try {
    optics_preset("arf");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "optics: unknown preset 'arf' (duv193, euv)");
  }
}
