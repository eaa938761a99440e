// The aerial image from the fields' spectra: on a grid by FFTW, at points by the direct sum.
#include "linf/litho/image.hpp"

#include <fftw3.h>

#include <cmath>
#include <cstring>
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

// The two plans of an m x m grid with `rows` nonzero rows: made once a process and kept. With
// FFTW_ESTIMATE: at m = 128 (the report's and the editor's pictures) FFTW_MEASURE's plans ran
// 8 pictures in 10 ms against 13 ms, but took 0.15 s to make, which a run's few pictures never
// win back (measured here).
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
  p.along_x = fftw_plan_many_dft(1, &m, rows, a, nullptr, 1, m, a, nullptr, 1, m, FFTW_BACKWARD, FFTW_ESTIMATE);
  p.along_y = fftw_plan_many_dft(1, &m, m, b, nullptr, m, 1, b, nullptr, m, 1, FFTW_BACKWARD, FFTW_ESTIMATE);
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
      for (std::size_t a = 0; a < n; ++a)
        for (std::size_t b = 0; b < n; ++b) {
          // values[i][r * n + c] is frequency (r - h, c - h): along x, a is r; along y, a is c.
          const cd v = kernels.values[i][axis == 0 ? a * n + b : b * n + a];
          re_[axis][(i * n + a) * n + b] = v.real();
          im_[axis][(i * n + a) * n + b] = v.imag();
          if (v != cd(0)) lo_[axis][a] = std::min(lo_[axis][a], b), hi_[axis][a] = std::max(hi_[axis][a], b + 1);
        }
  }
}

namespace {

// Lines are profiled kLanes at a time: the sums below run over them side by side.
constexpr std::size_t kLanes = 8;

// s_j = sum over b in [lo, hi) of k[b] m_j[b] and t_j = sum of l[b] m_j[b], for two kernels k
// and l of the same span and kLanes lines j, complex in parts, m_j[b] at m[b * kLanes + j]: each
// mask value is loaded once for both kernels, one kernel value serves all the lines from a
// register, the partial sums stay in registers, and each line's sum is taken in the order of b,
// whatever the clone (products and sums apart, never fused, so the same bits from every clone;
// a kernel's sums do not depend on the other kernel of its pair).
using Quad = double __attribute__((vector_size(4 * sizeof(double))));

__attribute__((target_clones("avx2", "default"))) void dot_lanes2(const double* kr, const double* ki,
                                                                   const double* lr, const double* li,
                                                                   const double* mr, const double* mi,
                                                                   std::size_t lo, std::size_t hi, double* sr,
                                                                   double* si, double* tr, double* ti) {
  static_assert(kLanes == 8, "two quads of lanes");
  Quad ar0 = {}, ar1 = {}, ai0 = {}, ai1 = {}, br0 = {}, br1 = {}, bi0 = {}, bi1 = {};
  for (std::size_t b = lo; b < hi; ++b) {
    Quad vr0, vr1, vi0, vi1;
    std::memcpy(&vr0, mr + b * kLanes, sizeof vr0);
    std::memcpy(&vr1, mr + b * kLanes + 4, sizeof vr1);
    std::memcpy(&vi0, mi + b * kLanes, sizeof vi0);
    std::memcpy(&vi1, mi + b * kLanes + 4, sizeof vi1);
    const double r = kr[b], q = ki[b];
    ar0 += r * vr0 - q * vi0;
    ar1 += r * vr1 - q * vi1;
    ai0 += r * vi0 + q * vr0;
    ai1 += r * vi1 + q * vr1;
    const double u = lr[b], v = li[b];
    br0 += u * vr0 - v * vi0;
    br1 += u * vr1 - v * vi1;
    bi0 += u * vi0 + v * vr0;
    bi1 += u * vi1 + v * vr1;
  }
  std::memcpy(sr, &ar0, sizeof ar0);
  std::memcpy(sr + 4, &ar1, sizeof ar1);
  std::memcpy(si, &ai0, sizeof ai0);
  std::memcpy(si + 4, &ai1, sizeof ai1);
  std::memcpy(tr, &br0, sizeof br0);
  std::memcpy(tr + 4, &br1, sizeof br1);
  std::memcpy(ti, &bi0, sizeof bi0);
  std::memcpy(ti + 4, &bi1, sizeof bi1);
}

}  // namespace

LineProfile::LineProfile(const LineKernels& lk, const MaskSpectrum& mask, double px, double py, double dx, double dy)
    : px_(px), py_(py) {
  *this = std::move(batch(lk, {Probe{&mask, px, py, dx, dy}}).front());
}

std::vector<LineProfile> LineProfile::batch(const LineKernels& kernels, const std::vector<Probe>& probes) {
  return std::move(batch(std::vector<const LineKernels*>{&kernels}, probes).front());
}

std::vector<std::vector<LineProfile>> LineProfile::batch(const std::vector<const LineKernels*>& sets,
                                                         const std::vector<Probe>& probes) {
  if (sets.empty()) throw std::invalid_argument("line profiles: no kernels");
  const Kernels& first = sets.front()->kernels();
  for (const LineKernels* lk : sets)
    if (lk->kernels().period != first.period || lk->kernels().size != first.size)
      throw std::invalid_argument("line profiles: the kernel sets differ in period or size");
  std::vector<std::vector<LineProfile>> out(sets.size());
  for (std::size_t set = 0; set < sets.size(); ++set) {
    const Kernels& kernels = sets[set]->kernels();
    out[set].reserve(probes.size());
    for (const Probe& p : probes) {
      out[set].push_back(LineProfile(p.px, p.py));
      LineProfile& line = out[set].back();
      line.direction(p.dx, p.dy);
      if (!line.axis_) {
        line.owned_ = std::make_shared<const AerialImage>(kernels, *p.mask);
        line.image_ = line.owned_.get();
        continue;
      }
      if (p.mask->period() != kernels.period)
        throw std::invalid_argument("aerial image: the mask's period is not the kernels' period");
      if (p.mask->half() < kernels.half())
        throw std::invalid_argument("aerial image: the mask has fewer frequencies than the kernels");
    }
  }
  // As LineProfile(image, ...), with the field K_i(kx, ky) c(kx, ky) never stored: each mask
  // times the phases across its line is formed once, for every kernel set, then each kernel
  // adds its products frequency by frequency, to every line along the same axis in turn.
  const int h = first.half();
  const std::size_t n = std::size_t(first.size);
  const double w = 2 * kPi / first.period;
  for (int axis = 0; axis < 2; ++axis) {
    const bool along_x = axis == 0;
    std::vector<std::size_t> mine;
    for (std::size_t k = 0; k < probes.size(); ++k)
      if (out[0][k].axis_ && (out[0][k].dy_ == 0) == along_x) mine.push_back(k);
    if (mine.empty()) continue;
    const std::size_t lines = mine.size(), groups = (lines + kLanes - 1) / kLanes;
    // [((g * n + a) * n + b) * kLanes + j]: line g kLanes + j's mask at a along the line, b
    // across it, times across[b]; lanes beyond the last line stay zero.
    std::vector<double> mr(groups * n * n * kLanes, 0.0), mi(groups * n * n * kLanes, 0.0);
    std::vector<cd> along(lines * n), across(n);
    for (std::size_t j = 0; j < lines; ++j) {
      const Probe& p = probes[mine[j]];
      phases(w * (along_x ? p.py : p.px), h, across.data());
      phases(w * (along_x ? p.px : p.py), h, &along[j * n]);
      const std::size_t g = j / kLanes, lane = j % kLanes;
      for (int a = -h; a <= h; ++a)
        for (int b = -h; b <= h; ++b) {
          const cd v = (along_x ? p.mask->at(a, b) : p.mask->at(b, a)) * across[std::size_t(b + h)];
          const std::size_t at = ((g * n + std::size_t(a + h)) * n + std::size_t(b + h)) * kLanes + lane;
          mr[at] = v.real();
          mi[at] = v.imag();
        }
    }
    for (std::size_t set = 0; set < sets.size(); ++set) {
      const LineKernels& lk = *sets[set];
      const std::size_t count = lk.kernels().count();
      // [(j * count + i) * n + a]: line j's kernel i at frequency a along the line.
      std::vector<double> re(lines * count * n), im(lines * count * n);
      const double* kr = lk.re_[axis].data();
      const double* ki = lk.im_[axis].data();
      double sr[kLanes], si[kLanes], tr[kLanes], ti[kLanes];
      auto put = [&](std::size_t g, std::size_t i, std::size_t a, const double* r, const double* q) {
        for (std::size_t lane = 0; lane < kLanes && g * kLanes + lane < lines; ++lane) {
          const std::size_t j = g * kLanes + lane;
          re[(j * count + i) * n + a] = r[lane];
          im[(j * count + i) * n + a] = q[lane];
        }
      };
      for (std::size_t g = 0; g < groups; ++g)
        for (std::size_t i = 0; i < count; i += 2)
          for (std::size_t a = 0; a < n; ++a) {
            const std::size_t at = (i * n + a) * n, m = (g * n + a) * n * kLanes;
            const std::size_t lo = lk.lo_[axis][a], hi = std::max(lk.lo_[axis][a], lk.hi_[axis][a]);
            // An odd count's last kernel is paired with itself.
            const std::size_t next = i + 1 < count ? at + n * n : at;
            dot_lanes2(kr + at, ki + at, kr + next, ki + next, &mr[m], &mi[m], lo, hi, sr, si, tr, ti);
            put(g, i, a, sr, si);
            if (i + 1 < count) put(g, i + 1, a, tr, ti);
          }
      std::vector<double> line_re(count * n), line_im(count * n);
      for (std::size_t j = 0; j < lines; ++j) {
        const double* r = &re[j * count * n];
        const double* q = &im[j * count * n];
        for (std::size_t i = 0; i < count; ++i)
          for (std::size_t a = 0; a < n; ++a) {
            const cd c = cd(r[i * n + a], q[i * n + a]) * along[j * n + a];
            line_re[i * n + a] = c.real();
            line_im[i * n + a] = c.imag();
          }
        LineProfile& line = out[set][mine[j]];
        line.omega_ = w * (along_x ? line.dx_ : line.dy_);
        line.fold(line_re, line_im, lk.kernels().weights, n);
      }
    }
  }
  return out;
}

namespace {

// Sixteen terms of the fold at once: g[d0 + e] for e < 16 over every kernel i and every a with
// a + d0 < n, as sum_i sum_a c_i(a + d0 + e) (u_i(a) + i v_i(a)), in that order (kernel by
// kernel, a ascending), the partial sums in registers. c_i is padded with 16 zeros past n, so
// lanes whose a + d0 + e >= n add only zeros. Products and sums apart, never fused: the same
// bits from every clone.
__attribute__((target_clones("avx2", "default"))) void fold_lanes(const double* cr, const double* ci,
                                                                   const double* u, const double* v,
                                                                   std::size_t kernels, std::size_t n,
                                                                   std::size_t stride, std::size_t d0, double* gr,
                                                                   double* gi) {
  Quad ar[4] = {}, ai[4] = {};
  for (std::size_t i = 0; i < kernels; ++i)
    for (std::size_t a = 0; a + d0 < n; ++a) {
      const double x = u[i * n + a], y = v[i * n + a];
      if (x == 0 && y == 0) continue;
      const double* r = cr + i * stride + a + d0;
      const double* q = ci + i * stride + a + d0;
      for (int e = 0; e < 4; ++e) {
        Quad vr, vi;
        std::memcpy(&vr, r + 4 * e, sizeof vr);
        std::memcpy(&vi, q + 4 * e, sizeof vi);
        ar[e] += vr * x - vi * y;
        ai[e] += vr * y + vi * x;
      }
    }
  std::memcpy(gr, ar, sizeof ar);
  std::memcpy(gi, ai, sizeof ai);
}

}  // namespace

void LineProfile::fold(const std::vector<double>& re, const std::vector<double>& im, const std::vector<double>& weights,
                       std::size_t n) {
  // |sum_a c_a z^a|^2 = sum_d (sum_a c_(a+d) conj(c_a)) z^d over d = -2h..2h, and the terms at
  // -d are the conjugates of those at d: only d = 0..2h are kept. The term of a is
  // c_(a+d) w conj(c_a); a kernel's a where c_a is zero adds nothing and is skipped.
  const std::size_t count = weights.size(), stride = n + 16;
  std::vector<double> cr(count * stride, 0.0), ci(count * stride, 0.0), u(count * n), v(count * n);
  for (std::size_t i = 0; i < count; ++i)
    for (std::size_t a = 0; a < n; ++a) {
      cr[i * stride + a] = re[i * n + a];
      ci[i * stride + a] = im[i * n + a];
      u[i * n + a] = re[i * n + a] == 0 && im[i * n + a] == 0 ? 0.0 : weights[i] * re[i * n + a];
      v[i * n + a] = re[i * n + a] == 0 && im[i * n + a] == 0 ? 0.0 : -weights[i] * im[i * n + a];
    }
  g_.resize(n);
  double gr[16], gi[16];
  for (std::size_t d0 = 0; d0 < n; d0 += 16) {
    fold_lanes(cr.data(), ci.data(), u.data(), v.data(), count, n, stride, d0, gr, gi);
    for (std::size_t e = 0; e < 16 && d0 + e < n; ++e) g_[d0 + e] = cd(gr[e], gi[e]);
  }
}

namespace {

// The plan of a forward m x m transform, made once a size (FFTW_ESTIMATE, under the planner's lock).
fftw_plan forward_plan(int m) {
  static std::map<int, fftw_plan> made;
  std::lock_guard<std::mutex> lock(planner_lock());
  auto it = made.find(m);
  if (it != made.end()) return it->second;
  fftw_complex* a = fftw_alloc_complex(std::size_t(m) * std::size_t(m));
  const fftw_plan p = fftw_plan_dft_2d(m, m, a, a, FFTW_FORWARD, FFTW_ESTIMATE);
  fftw_free(a);
  made.emplace(m, p);
  return p;
}

// The spectrum of an m x m grid of real values (value [j * m + i], j along y): [(e mod m) * m
// + (d mod m)] the coefficient of exp(2 pi i (d x + e y) / P), x = i P / m.
std::vector<cd> grid_spectrum(const std::vector<double>& values, int m) {
  const std::size_t mm = std::size_t(m) * std::size_t(m);
  fftw_complex* a = fftw_alloc_complex(mm);
  for (std::size_t k = 0; k < mm; ++k) a[k][0] = values[k], a[k][1] = 0;
  fftw_execute_dft(forward_plan(m), a, a);
  std::vector<cd> out(mm);
  for (std::size_t k = 0; k < mm; ++k) out[k] = cd(a[k][0], a[k][1]) / double(mm);
  fftw_free(a);
  return out;
}

}  // namespace

void blur_grid(std::vector<double>& values, int m, double period, double sigma) {
  if (!(sigma >= 0) || !std::isfinite(sigma)) throw std::invalid_argument("blur: sigma must be a number >= 0");
  if (m < 1 || values.size() != std::size_t(m) * std::size_t(m)) throw std::invalid_argument("blur: not an m x m grid");
  if (sigma == 0) return;
  std::vector<cd> spectrum = grid_spectrum(values, m);
  const double w = 2 * kPi / period;
  auto freq = [m](int k) { return k <= m / 2 ? k : k - m; };
  // Back by the inverse transform's plans (the grid's own: every row nonzero).
  const GridPlans plans = grid_plans(m, m);
  const std::size_t mm = std::size_t(m) * std::size_t(m);
  fftw_complex* a = fftw_alloc_complex(mm);
  for (int e = 0; e < m; ++e)
    for (int d = 0; d < m; ++d) {
      const double u = w * freq(d), v = w * freq(e);
      const cd c = spectrum[std::size_t(e) * std::size_t(m) + std::size_t(d)] * std::exp(-0.5 * sigma * sigma * (u * u + v * v));
      a[std::size_t(e) * std::size_t(m) + std::size_t(d)][0] = c.real();
      a[std::size_t(e) * std::size_t(m) + std::size_t(d)][1] = c.imag();
    }
  fftw_execute_dft(plans.along_x, a, a);  // every row along x, then every column along y
  fftw_execute_dft(plans.along_y, a, a);
  for (std::size_t k = 0; k < mm; ++k) values[k] = a[k][0];
  fftw_free(a);
}

void LineProfile::blur(double sigma) {
  if (!(sigma >= 0) || !std::isfinite(sigma)) throw std::invalid_argument("line profile: the blur must be a number >= 0");
  if (sigma == 0) return;
  if (axis_) {
    for (std::size_t d = 1; d < g_.size(); ++d) g_[d] *= std::exp(-0.5 * sigma * sigma * (omega_ * double(d)) * (omega_ * double(d)));
    return;
  }
  // The image's frequencies reach 2h a side: a grid of more than 4h samples holds them exactly.
  const int h = image_->half(), q = 2 * h;
  int m = 8;
  while (m <= 2 * q) m *= 2;
  const std::vector<cd> full = grid_spectrum(image_->grid(m, 1), m);
  const double w = 2 * kPi / image_->period();
  const std::size_t side = std::size_t(2 * q + 1);
  spectrum_.assign(side * side, cd(0));
  for (int d = -q; d <= q; ++d)
    for (int e = -q; e <= q; ++e) {
      const double along = w * (d * dx_ + e * dy_);
      spectrum_[std::size_t(d + q) * side + std::size_t(e + q)] =
          full[std::size_t((e + m) % m) * std::size_t(m) + std::size_t((d + m) % m)] * std::exp(-0.5 * sigma * sigma * along * along);
    }
  q_ = q;
  omega_ = w;
}

double LineProfile::at(double t) const {
  if (!axis_ && spectrum_.empty()) return image_->at(px_ + t * dx_, py_ + t * dy_);
  if (!axis_) {
    // The blurred image's band-limited sum at the point, frequency along x outermost.
    const std::size_t side = std::size_t(2 * q_ + 1);
    std::vector<cd> ex(side), ey(side);
    phases(omega_ * (px_ + t * dx_), q_, ex.data());
    phases(omega_ * (py_ + t * dy_), q_, ey.data());
    cd sum = 0;
    for (std::size_t d = 0; d < side; ++d) {
      cd row = 0;
      for (std::size_t e = 0; e < side; ++e) row += spectrum_[d * side + e] * ey[e];
      sum += row * ex[d];
    }
    return sum.real();
  }
  // g_0 + 2 Re sum_{d >= 1} g_d z^d, z = exp(i omega t), as z sum_r z^r Q_r(z^4) with
  // Q_r(w) = sum_k g_(4k + r + 1) w^k: four Horner chains side by side (one chain waits on each
  // product before the next; a reading evaluates a line about 40 times).
  const cd z = std::polar(1.0, omega_ * t), z2 = z * z, w = z2 * z2;
  const std::size_t terms = g_.size() - 1;  // d = 1..terms
  cd q[4] = {0, 0, 0, 0};
  for (std::size_t k = (terms + 3) / 4; k-- > 0;)
    for (std::size_t r = 0; r < 4; ++r) {
      const std::size_t d = 4 * k + r + 1;
      q[r] = q[r] * w + (d <= terms ? g_[d] : cd(0));
    }
  const cd p = z * (q[0] + z * (q[1] + z * (q[2] + z * q[3])));
  return g_[0].real() + 2 * p.real();
}

}  // namespace linf::litho
