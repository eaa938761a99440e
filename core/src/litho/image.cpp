// The aerial image from the fields' spectra: on a grid by FFTW, at points by the direct sum.
#include "linf/litho/image.hpp"

#include <fftw3.h>

#include <cmath>
#include <map>
#include <mutex>
#include <utility>
#include <stdexcept>

#include "util/parallel.hpp"

namespace linf::litho {
namespace {

using cd = std::complex<double>;
constexpr double kPi = 3.14159265358979323846;

// exp(i theta k) for k = -h..h into out[0..2h], by powers of one exponential (2h products:
// a relative error of a few times 2h ulps, far below the kernels' float32 precision).
void phases(double theta, int h, cd* out) {
  const cd base = std::polar(1.0, theta);
  out[h] = 1;
  cd up = 1;
  for (int k = 1; k <= h; ++k) {
    up *= base;
    out[h + k] = up;
    out[h - k] = std::conj(up);
  }
}

// FFTW's planner is not thread-safe; plans are made and destroyed under this lock (executing
// a plan on other arrays, fftw_execute_dft, is safe from any thread).
std::mutex& planner_lock() {
  static std::mutex m;
  return m;
}

// The two plans of an m x m grid with `rows` nonzero rows: made once a process with
// FFTW_MEASURE (at m = 256 its plans run about 8 times faster than FFTW_ESTIMATE's, measured
// here) and kept, so only the first grid of a size pays the planning (a fraction of a second).
struct GridPlans {
  fftw_plan along_x, along_y;
};
GridPlans grid_plans(int m, int rows) {
  static std::map<std::pair<int, int>, GridPlans> made;
  std::lock_guard<std::mutex> lock(planner_lock());
  auto it = made.find({m, rows});
  if (it != made.end()) return it->second;
  const std::size_t mm = std::size_t(m) * std::size_t(m);
  fftw_complex* a = fftw_alloc_complex(std::size_t(rows) * std::size_t(m));
  fftw_complex* b = fftw_alloc_complex(mm);
  // `rows` rows of m contiguous values; then m columns of m values, m apart.
  GridPlans p;
  p.along_x = fftw_plan_many_dft(1, &m, rows, a, nullptr, 1, m, a, nullptr, 1, m, FFTW_BACKWARD, FFTW_MEASURE);
  p.along_y = fftw_plan_many_dft(1, &m, m, b, nullptr, m, 1, b, nullptr, m, 1, FFTW_BACKWARD, FFTW_MEASURE);
  fftw_free(a);
  fftw_free(b);
  made.emplace(std::make_pair(m, rows), p);
  return p;
}

}  // namespace

AerialImage::AerialImage(const Kernels& kernels, const MaskSpectrum& mask)
    : period_(kernels.period), half_(kernels.half()), weights_(kernels.weights) {
  if (kernels.count() == 0) throw std::invalid_argument("aerial image: no kernels");
  if (mask.period() != kernels.period)
    throw std::invalid_argument("aerial image: the mask's period is not the kernels' period");
  if (mask.half() < half_) throw std::invalid_argument("aerial image: the mask has fewer frequencies than the kernels");
  const std::size_t n = std::size_t(2 * half_ + 1);
  fields_.resize(kernels.count() * n * n);
  for (std::size_t i = 0; i < kernels.count(); ++i)
    for (int kx = -half_; kx <= half_; ++kx)
      for (int ky = -half_; ky <= half_; ++ky)
        fields_[i * n * n + std::size_t(kx + half_) * n + std::size_t(ky + half_)] =
            kernels.at(i, kx, ky) * mask.at(kx, ky);
}

double AerialImage::at(double x, double y) const {
  const std::size_t n = std::size_t(2 * half_ + 1);
  std::vector<cd> ex(n), ey(n);
  phases(2 * kPi * x / period_, half_, ex.data());
  phases(2 * kPi * y / period_, half_, ey.data());
  double sum = 0;
  for (std::size_t i = 0; i < weights_.size(); ++i) {
    const cd* f = &fields_[i * n * n];
    cd e = 0;
    for (std::size_t a = 0; a < n; ++a) {
      cd row = 0;
      for (std::size_t b = 0; b < n; ++b) row += f[a * n + b] * ey[b];
      e += row * ex[a];
    }
    sum += weights_[i] * std::norm(e);
  }
  return sum;
}

std::vector<double> AerialImage::grid(int m, int threads) const {
  if (m < 2 * half_ + 1) throw std::invalid_argument("aerial image: the grid must have at least 2 * half + 1 pixels a side");
  // A field's spectrum is nonzero on 2h + 1 rows only (|ky| <= h): the transforms along x are
  // done on those rows alone, then the transforms along y on every column: (2h + 1) + m
  // transforms of length m instead of the 2 m of a full 2-D transform.
  const int rows = 2 * half_ + 1;
  const std::size_t mm = std::size_t(m) * std::size_t(m), compact = std::size_t(rows) * std::size_t(m), n = std::size_t(rows);
  const GridPlans plans = grid_plans(m, rows);
  const fftw_plan along_x = plans.along_x, along_y = plans.along_y;
  const unsigned workers = detail::worker_count(weights_.size(), threads);
  std::vector<std::vector<double>> partial(workers, std::vector<double>(mm, 0.0));
  std::vector<fftw_complex*> rows_buf(workers), full_buf(workers);
  for (unsigned w = 0; w < workers; ++w) {
    rows_buf[w] = fftw_alloc_complex(compact);
    full_buf[w] = fftw_alloc_complex(mm);
  }
  detail::parallel_for(weights_.size(), int(workers), [&](unsigned w, std::size_t i) {
    fftw_complex* r = rows_buf[w];
    fftw_complex* f = full_buf[w];
    // Compact row ky + h holds frequency ky; column kx wraps to the end of the row when negative.
    for (std::size_t p = 0; p < compact; ++p) r[p][0] = r[p][1] = 0;
    for (int kx = -half_; kx <= half_; ++kx)
      for (int ky = -half_; ky <= half_; ++ky) {
        const cd v = fields_[i * n * n + std::size_t(kx + half_) * n + std::size_t(ky + half_)];
        const std::size_t at = std::size_t(ky + half_) * std::size_t(m) + std::size_t((kx + m) % m);
        r[at][0] = v.real();
        r[at][1] = v.imag();
      }
    fftw_execute_dft(along_x, r, r);
    // Row j of the full array is frequency ky = j (j <= h) or j - m (j >= m - h); others zero.
    for (std::size_t p = 0; p < mm; ++p) f[p][0] = f[p][1] = 0;
    for (int ky = -half_; ky <= half_; ++ky) {
      const fftw_complex* from = r + std::size_t(ky + half_) * std::size_t(m);
      fftw_complex* to = f + std::size_t((ky + m) % m) * std::size_t(m);
      for (int x = 0; x < m; ++x) {
        to[x][0] = from[x][0];
        to[x][1] = from[x][1];
      }
    }
    fftw_execute_dft(along_y, f, f);
    const double wt = weights_[i];
    double* out = partial[w].data();
    for (std::size_t p = 0; p < mm; ++p) out[p] += wt * (f[p][0] * f[p][0] + f[p][1] * f[p][1]);
  });
  for (unsigned w = 0; w < workers; ++w) {
    fftw_free(rows_buf[w]);
    fftw_free(full_buf[w]);
  }
  for (unsigned w = 1; w < workers; ++w)
    for (std::size_t p = 0; p < mm; ++p) partial[0][p] += partial[w][p];
  return std::move(partial[0]);
}

void LineProfile::direction(double dx, double dy) {
  const double len = std::hypot(dx, dy);
  if (!(len > 0)) throw std::invalid_argument("line profile: the direction must not be zero");
  dx_ = dx / len;
  dy_ = dy / len;
  axis_ = (dx_ == 0 || dy_ == 0);
}

LineProfile::LineProfile(const AerialImage& image, double px, double py, double dx, double dy)
    : image_(&image), px_(px), py_(py) {
  direction(dx, dy);
  if (!axis_) return;
  // Along x (dy = 0): E_i(t) = sum_kx exp(2 pi i kx (px + t dx) / P) * sum_ky F_i(kx, ky) exp(2 pi i ky py / P);
  // the inner sums and the phase of p are folded into one coefficient a kx. Along y alike.
  const int h = image.half();
  const std::size_t n = std::size_t(2 * h + 1);
  std::vector<cd> across(n), along(n);
  const double w = 2 * kPi / image.period();
  const bool along_x = dy_ == 0;
  phases(w * (along_x ? py : px), h, across.data());
  phases(w * (along_x ? px : py), h, along.data());
  std::vector<double> re(image.kernel_count() * n), im(image.kernel_count() * n), weights(image.kernel_count());
  for (std::size_t i = 0; i < image.kernel_count(); ++i) {
    weights[i] = image.weight(i);
    for (int a = -h; a <= h; ++a) {  // a: the frequency along the line
      cd s = 0;
      for (int b = -h; b <= h; ++b) s += (along_x ? image.field(i, a, b) : image.field(i, b, a)) * across[std::size_t(b + h)];
      const cd c = s * along[std::size_t(a + h)];
      re[i * n + std::size_t(a + h)] = c.real();
      im[i * n + std::size_t(a + h)] = c.imag();
    }
  }
  omega_ = w * (along_x ? dx_ : dy_);
  fold(re, im, weights, n);
}

LineKernels::LineKernels(const Kernels& kernels) : kernels_(&kernels), n_(std::size_t(kernels.size)) {
  if (kernels.count() == 0) throw std::invalid_argument("aerial image: no kernels");
  const std::size_t n = n_, count = kernels.count();
  for (int axis = 0; axis < 2; ++axis) {
    re_[axis].assign(count * n * n, 0.0);
    im_[axis].assign(count * n * n, 0.0);
    lo_[axis].assign(n, n);
    hi_[axis].assign(n, 0);
    for (std::size_t i = 0; i < count; ++i)
      for (std::size_t b = 0; b < n; ++b)
        for (std::size_t a = 0; a < n; ++a) {
          // values[i][r * n + c] is frequency (r - h, c - h): along x, a is r; along y, a is c.
          const cd v = kernels.values[i][axis == 0 ? a * n + b : b * n + a];
          re_[axis][(i * n + b) * n + a] = v.real();
          im_[axis][(i * n + b) * n + a] = v.imag();
          if (v != cd(0)) lo_[axis][b] = std::min(lo_[axis][b], a), hi_[axis][b] = std::max(hi_[axis][b], a + 1);
        }
  }
}

namespace {

// acc[a] += k[a] m[a] over a in [lo, hi), complex in parts: elementwise, so vectorised without
// reordering a sum (the same bits from every clone).
__attribute__((target_clones("avx2", "default"))) void multiply_add(const double* kr, const double* ki,
                                                                     const double* mr, const double* mi, double* ar,
                                                                     double* ai, std::size_t lo, std::size_t hi) {
  for (std::size_t a = lo; a < hi; ++a) {
    ar[a] += kr[a] * mr[a] - ki[a] * mi[a];
    ai[a] += kr[a] * mi[a] + ki[a] * mr[a];
  }
}

}  // namespace

LineProfile::LineProfile(const LineKernels& lk, const MaskSpectrum& mask, double px, double py, double dx, double dy)
    : px_(px), py_(py) {
  const Kernels& kernels = lk.kernels();
  direction(dx, dy);
  if (!axis_) {
    owned_ = std::make_shared<const AerialImage>(kernels, mask);
    image_ = owned_.get();
    return;
  }
  if (mask.period() != kernels.period)
    throw std::invalid_argument("aerial image: the mask's period is not the kernels' period");
  if (mask.half() < kernels.half()) throw std::invalid_argument("aerial image: the mask has fewer frequencies than the kernels");
  // As above, with the field K_i(kx, ky) c(kx, ky) never stored: the mask times the phases
  // across the line is formed once, then each kernel adds its products frequency by frequency.
  const int h = kernels.half();
  const std::size_t n = lk.n_;
  std::vector<cd> across(n), along(n);
  const double w = 2 * kPi / kernels.period;
  const bool along_x = dy_ == 0;
  const int axis = along_x ? 0 : 1;
  phases(w * (along_x ? py : px), h, across.data());
  phases(w * (along_x ? px : py), h, along.data());
  // [b * n + a]: the mask at a along the line, b across it, times across[b].
  std::vector<double> mr(n * n), mi(n * n);
  for (int b = -h; b <= h; ++b)
    for (int a = -h; a <= h; ++a) {
      const cd v = (along_x ? mask.at(a, b) : mask.at(b, a)) * across[std::size_t(b + h)];
      mr[std::size_t(b + h) * n + std::size_t(a + h)] = v.real();
      mi[std::size_t(b + h) * n + std::size_t(a + h)] = v.imag();
    }
  const std::size_t count = kernels.count();
  std::vector<double> re(count * n, 0.0), im(count * n, 0.0);
  const double* kr = lk.re_[axis].data();
  const double* ki = lk.im_[axis].data();
  for (std::size_t i = 0; i < count; ++i) {
    double* ar = &re[i * n];
    double* ai = &im[i * n];
    for (std::size_t b = 0; b < n; ++b) {
      const std::size_t at = (i * n + b) * n;
      multiply_add(kr + at, ki + at, &mr[b * n], &mi[b * n], ar, ai, lk.lo_[axis][b], lk.hi_[axis][b]);
    }
    for (std::size_t a = 0; a < n; ++a) {
      const cd c = cd(ar[a], ai[a]) * along[a];
      ar[a] = c.real();
      ai[a] = c.imag();
    }
  }
  omega_ = w * (along_x ? dx_ : dy_);
  fold(re, im, kernels.weights, n);
}

namespace {

// g[d] += c[a + d] * (u + i v) for d in [0, n - a): elementwise, as multiply_add.
__attribute__((target_clones("avx2", "default"))) void fold_row(const double* cr, const double* ci, double u, double v,
                                                                 double* gr, double* gi, std::size_t count) {
  for (std::size_t d = 0; d < count; ++d) {
    gr[d] += cr[d] * u - ci[d] * v;
    gi[d] += cr[d] * v + ci[d] * u;
  }
}

}  // namespace

void LineProfile::fold(const std::vector<double>& re, const std::vector<double>& im, const std::vector<double>& weights,
                       std::size_t n) {
  // |sum_a c_a z^a|^2 = sum_d (sum_a c_(a+d) conj(c_a)) z^d over d = -2h..2h, and the terms at
  // -d are the conjugates of those at d: only d = 0..2h are kept.
  std::vector<double> gr(n, 0.0), gi(n, 0.0);
  for (std::size_t i = 0; i < weights.size(); ++i) {
    const double* cr = &re[i * n];
    const double* ci = &im[i * n];
    for (std::size_t a = 0; a < n; ++a) {
      if (cr[a] == 0 && ci[a] == 0) continue;
      fold_row(cr + a, ci + a, weights[i] * cr[a], -weights[i] * ci[a], gr.data(), gi.data(), n - a);
    }
  }
  g_.resize(n);
  for (std::size_t d = 0; d < n; ++d) g_[d] = cd(gr[d], gi[d]);
}

double LineProfile::at(double t) const {
  if (!axis_) return image_->at(px_ + t * dx_, py_ + t * dy_);
  // Horner's rule in z = exp(i omega t) over d = 1..2h: g_0 + 2 Re(z (g_1 + z (g_2 + ...))).
  const cd z = std::polar(1.0, omega_ * t);
  cd p = 0;
  for (std::size_t d = g_.size() - 1; d >= 1; --d) p = (p + g_[d]) * z;
  return g_[0].real() + 2 * p.real();
}

}  // namespace linf::litho
