// The exact Fourier coefficients of a window's polygons (mask.hpp).
//
// Green's theorem: for a counter-clockwise ring, integral over its inside of f equals
// -sum over its edges of integral along the edge of G(x, y) dx, with G(x, y) = integral from 0
// to y of f(x, t) dt. With f = exp(-i (a x + b y)), G = exp(-i a x) g(y), g(y) = integral from
// 0 to y of exp(-i b t) dt: each edge gives the transform of the trapezoid between it and y = 0.
// A vertical edge gives nothing; a horizontal one (most of a layout) gives a product of a
// function of kx and one of ky, so its 35 x 35 coefficients cost 2 x 35 exponentials.
#include "linf/litho/mask.hpp"

#include <cmath>
#include <cstring>
#include <map>
#include <sstream>
#include <stdexcept>

namespace linf::litho {
namespace {

using cd = std::complex<double>;
constexpr double kPi = 3.14159265358979323846;

double sinc(double u) { return std::abs(u) < 1e-4 ? 1 - u * u / 6 : std::sin(u) / u; }

// integral from a to b of exp(-i g x) dx, without cancellation for small g.
cd phi(double g, double a, double b) {
  const double m = 0.5 * (a + b), h = 0.5 * (b - a);
  return (b - a) * sinc(g * h) * std::polar(1.0, -g * m);
}

// integral along the edge (xa, ya) -> (xb, yb) of exp(-i a x) g(y(x)) dx, any slope.
cd slanted_edge(double a, double b, double xa, double ya, double xb, double yb) {
  const double s = (yb - ya) / (xb - xa);
  if (b == 0) {
    if (a == 0) return (xb - xa) * (ya + yb) / 2;
    const cd ia(0, a);
    return (yb * std::polar(1.0, -a * xb) - ya * std::polar(1.0, -a * xa)) / -ia + s / ia * phi(a, xa, xb);
  }
  const cd ib(0, b);
  return (phi(a, xa, xb) - std::polar(1.0, -b * (ya - s * xa)) * phi(a + b * s, xa, xb)) / ib;
}

// out[k + half] = scale * phi(step * k, a, b) for k = -half..half, by powers of two
// exponentials instead of 2 (2 half + 1) of them: phi(g, a, b) = 2 sin(g h) / g exp(-i g m),
// h the half-length, m the middle (the powers' error, a few times half ulps, is far below the
// kernels' float32 precision, as in the image's phases).
void edge_integrals(double step, double a, double b, int half, double scale, cd* out) {
  const double m = 0.5 * (a + b), h = 0.5 * (b - a);
  const cd e = std::polar(1.0, -step * m), s = std::polar(1.0, step * h);
  cd pe = 1, ps = 1;
  out[half] = scale * (b - a);
  for (int k = 1; k <= half; ++k) {
    pe *= e;
    ps *= s;
    const double v = scale * 2 * ps.imag() / (step * k);
    out[half + k] = v * pe;
    out[half - k] = v * std::conj(pe);
  }
}

using Quad = double __attribute__((vector_size(4 * sizeof(double))));

// c[a][b] += sum over the heights h, in order, of f_h(a) g_h(b), for a in [from, n) and all b,
// complex in parts: f at [h * n + a], g at [h * stride + b] (stride a multiple of 8, zero past
// n), c at [a * stride + b]. Eight b at a time, the partial sums in registers over every height
// (a row at a time would load and store c once a height); each c[a][b] still adds its heights'
// products one by one in order, products and sums never fused: the same bits from every clone
// as adding the products height by height.
__attribute__((target_clones("avx2", "default"))) void add_products(const double* fr, const double* fi,
                                                                     const double* gr, const double* gi,
                                                                     std::size_t heights, std::size_t n,
                                                                     std::size_t stride, std::size_t from, double* cr,
                                                                     double* ci) {
  for (std::size_t a = from; a < n; ++a)
    for (std::size_t b = 0; b < n; b += 8) {
      double* r = cr + a * stride + b;
      double* q = ci + a * stride + b;
      Quad r0, r1, q0, q1;
      std::memcpy(&r0, r, sizeof r0), std::memcpy(&r1, r + 4, sizeof r1);
      std::memcpy(&q0, q, sizeof q0), std::memcpy(&q1, q + 4, sizeof q1);
      for (std::size_t h = 0; h < heights; ++h) {
        const double x = fr[h * n + a], y = fi[h * n + a];
        Quad u0, u1, v0, v1;
        std::memcpy(&u0, gr + h * stride + b, sizeof u0), std::memcpy(&u1, gr + h * stride + b + 4, sizeof u1);
        std::memcpy(&v0, gi + h * stride + b, sizeof v0), std::memcpy(&v1, gi + h * stride + b + 4, sizeof v1);
        r0 += x * u0 - y * v0;
        r1 += x * u1 - y * v1;
        q0 += x * v0 + y * u0;
        q1 += x * v1 + y * u1;
      }
      std::memcpy(r, &r0, sizeof r0), std::memcpy(r + 4, &r1, sizeof r1);
      std::memcpy(q, &q0, sizeof q0), std::memcpy(q + 4, &q1, sizeof q1);
    }
}

}  // namespace

MaskSpectrum::MaskSpectrum(const std::vector<Polygon>& polygons, const Window& window, double period_nm, int half)
    : half_(half), period_(period_nm) {
  if (half < 0) throw std::invalid_argument("mask spectrum: the number of frequencies must not be negative");
  if (!(period_nm > 0) || !(window.dbu_nm > 0))
    throw std::invalid_argument("mask spectrum: the period and the database unit must be positive");
  const int n = 2 * half + 1;
  const std::size_t N = std::size_t(n);
  stride_ = (N + 7) / 8 * 8;
  re_.assign(N * stride_, 0.0);
  im_.assign(N * stride_, 0.0);
  bool slanted = false;
  const double step = 2 * kPi / period_nm;  // angular frequency of kx = 1, per nm
  std::vector<cd> fx(static_cast<std::size_t>(n)), fy(static_cast<std::size_t>(n));
  std::vector<double> xs, ys;
  std::map<double, std::size_t> height;  // a horizontal edge's y -> its row in `rows`
  std::vector<std::vector<cd>> rows;     // the sum of the functions of kx of the edges at that y
  for (const Polygon& polygon : polygons) {
    for (std::size_t r = 0; r <= polygon.holes.size(); ++r) {
      const Ring& ring = r == 0 ? polygon.outer : polygon.holes[r - 1];
      if (ring.size() < 3) continue;
      xs.clear();
      ys.clear();
      for (const Point& p : ring) {
        const double x = double(p.x - window.origin.x) * window.dbu_nm, y = double(p.y - window.origin.y) * window.dbu_nm;
        if (x < -1e-9 || y < -1e-9 || x > period_nm + 1e-9 || y > period_nm + 1e-9) {
          std::ostringstream s;
          s << "mask: the point (" << p.x << ", " << p.y << ") lies outside the window of " << period_nm
            << " nm from (" << window.origin.x << ", " << window.origin.y << ")";
          throw std::invalid_argument(s.str());
        }
        xs.push_back(x);
        ys.push_back(y);
      }
      double twice_area = 0;
      for (std::size_t i = 0, m = xs.size(); i < m; ++i) {
        const std::size_t j = (i + 1) % m;
        twice_area += xs[i] * ys[j] - xs[j] * ys[i];
      }
      if (twice_area == 0) continue;
      // Counter-clockwise outer rings count +1, holes -1, whatever their stored orientation;
      // Green's theorem brings the minus sign; the coefficients are divided by P^2.
      const double sign = (twice_area > 0 ? -1.0 : 1.0) * (r == 0 ? 1.0 : -1.0) / (period_nm * period_nm);
      for (std::size_t i = 0, m = xs.size(); i < m; ++i) {
        const std::size_t j = (i + 1) % m;
        const double xa = xs[i], ya = ys[i], xb = xs[j], yb = ys[j];
        if (xa == xb) continue;
        if (ya == yb) {
          // Horizontal edges at one height share their function of ky: their functions of kx
          // are summed first, the products formed once a height (below).
          auto [at, fresh] = height.try_emplace(ya, rows.size());
          if (fresh) rows.emplace_back(std::size_t(n), cd(0));
          edge_integrals(step, xa, xb, half, sign, fx.data());
          std::vector<cd>& row = rows[at->second];
          for (int k = 0; k < n; ++k) row[std::size_t(k)] += fx[std::size_t(k)];
        } else {
          slanted = true;
          for (int a = 0; a < n; ++a)
            for (int b = 0; b < n; ++b) {
              const cd v = sign * slanted_edge(step * (a - half), step * (b - half), xa, ya, xb, yb);
              re_[std::size_t(a) * stride_ + std::size_t(b)] += v.real();
              im_[std::size_t(a) * stride_ + std::size_t(b)] += v.imag();
            }
        }
      }
    }
  }
  // The mask is real, so c(-kx, -ky) = conj(c(kx, ky)). The heights' products have it to the
  // bit (each factor's values at -k are the conjugates of those at k, to the bit, and so are
  // their products and sums): without slanted edges only kx >= 0 is formed and the rest copied.
  // A slanted edge's sums are not symmetric to the bit; with one, every kx is formed.
  const std::size_t stride = stride_, heights = height.size();
  std::vector<double> fr(heights * N), fi(heights * N), gr(heights * stride, 0.0), gi(heights * stride, 0.0);
  std::size_t k = 0;
  for (const auto& [y, r] : height) {
    edge_integrals(step, 0, y, half, 1.0, fy.data());
    for (std::size_t b = 0; b < N; ++b) gr[k * stride + b] = fy[b].real(), gi[k * stride + b] = fy[b].imag();
    for (std::size_t a = 0; a < N; ++a) fr[k * N + a] = rows[r][a].real(), fi[k * N + a] = rows[r][a].imag();
    ++k;
  }
  const std::size_t from = slanted ? 0 : std::size_t(half);
  add_products(fr.data(), fi.data(), gr.data(), gi.data(), heights, N, stride, from, re_.data(), im_.data());
  if (!slanted)
    for (int a = 0; a < half; ++a)
      for (int b = 0; b < n; ++b) {
        const std::size_t to = std::size_t(a) * stride_ + std::size_t(b);
        const std::size_t mirror = std::size_t(n - 1 - a) * stride_ + std::size_t(n - 1 - b);
        re_[to] = re_[mirror];
        im_[to] = -im_[mirror];
      }
}

}  // namespace linf::litho
