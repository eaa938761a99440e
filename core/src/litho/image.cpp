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

LineProfile::LineProfile(const AerialImage& image, double px, double py, double dx, double dy)
    : image_(image), px_(px), py_(py), dx_(dx), dy_(dy) {
  const double len = std::hypot(dx, dy);
  if (!(len > 0)) throw std::invalid_argument("line profile: the direction must not be zero");
  dx_ /= len;
  dy_ /= len;
  axis_ = (dx_ == 0 || dy_ == 0);
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
  line_.assign(image.kernel_count() * n, cd(0));
  for (std::size_t i = 0; i < image.kernel_count(); ++i)
    for (int a = -h; a <= h; ++a) {  // a: the frequency along the line
      cd s = 0;
      for (int b = -h; b <= h; ++b) s += (along_x ? image.field(i, a, b) : image.field(i, b, a)) * across[std::size_t(b + h)];
      line_[i * n + std::size_t(a + h)] = s * along[std::size_t(a + h)];
    }
}

double LineProfile::at(double t) const {
  if (!axis_) return image_.at(px_ + t * dx_, py_ + t * dy_);
  const int h = image_.half();
  const std::size_t n = std::size_t(2 * h + 1);
  std::vector<cd> e(n);
  phases(2 * kPi * t * (dy_ == 0 ? dx_ : dy_) / image_.period(), h, e.data());
  double sum = 0;
  for (std::size_t i = 0; i < image_.kernel_count(); ++i) {
    const cd* c = &line_[i * n];
    cd f = 0;
    for (std::size_t a = 0; a < n; ++a) f += c[a] * e[a];
    sum += image_.weight(i) * std::norm(f);
  }
  return sum;
}

}  // namespace linf::litho
