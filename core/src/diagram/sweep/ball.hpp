// The balls of the sweep's circle events: a ball of N_eps = L-inf + eps L1 (eps.hpp) touching
// three sites, each point on one of the octagon's sides, each segment's line (axis-parallel or
// at 45 degrees) from the side its arc faces. The sides are found from the L-inf squares (eps = 0) through the
// sites; for each choice the centre solves a 3x3 linear system, exactly.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include "diagram/sweep/eps.hpp"

namespace linf::sweep {

// The eight sides of N_eps's unit ball, (alpha, beta) as c0 + c1 eps: N_eps(u, v) is the
// largest of alpha u + beta v. Then a segment's line touched by the ball: an axis-parallel one
// (N_eps of a point's distance to it is (1 + eps) times the L-inf one) with the ball left of
// (below, right of, above) it, sides 8-11; a 45-degree one, sides 12-15, lying in direction n
// from the ball, n = (1, 1), (1, -1), (-1, -1), (-1, 1). The ball reaches 2 r / (1 + 2 eps)
// in direction n (at the octagon's diagonal vertex): its row is -(1 + 2 eps) n . (c - p) = 2 r,
// the only sides whose radius column (kGamma) is not -1.
constexpr std::int64_t kAlpha[16][2] = {{1, 1},  {1, 1},   {-1, -1}, {-1, -1},  // x dominant, right; left
                                        {0, 1},  {0, -1},  {0, 1},   {0, -1},   // y dominant, up; down
                                        {-1, -1}, {0, 0},  {1, 1},   {0, 0},    // axis-parallel lines
                                        {-1, -2}, {-1, -2}, {1, 2},  {1, 2}};   // 45-degree lines
constexpr std::int64_t kBeta[16][2] = {{0, 1},  {0, -1},  {0, 1},   {0, -1},
                                       {1, 1},  {1, 1},   {-1, -1}, {-1, -1},
                                       {0, 0},  {-1, -1}, {0, 0},   {1, 1},
                                       {-1, -2}, {1, 2},  {1, 2},   {-1, -2}};
constexpr std::int64_t kGamma[16] = {-1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -2, -2, -2, -2};
constexpr int kSides = 16;
struct Side {
  Eps alpha, beta;
};
inline const Side* sides() {
  static const auto s = [] {
    std::array<Side, kSides> t;
    for (int k = 0; k < kSides; ++k) t[k] = {Eps::of(kAlpha[k][0], kAlpha[k][1]), Eps::of(kBeta[k][0], kBeta[k][1])};
    return t;
  }();
  return s.data();
}
// Side 8 + segment_side(...): the side of a segment's line that its arc (Boost's site event,
// possibly inverted) lies on: the right of point0 -> point1.
constexpr int kLineLeftOfIt = 8, kLineBelowIt = 9, kLineRightOfIt = 10, kLineAboveIt = 11;
constexpr int kDiagonal = 12;  // 12 + k: the line in direction kDiagonalN[k] from the ball
constexpr std::int64_t kDiagonalN[4][2] = {{1, 1}, {1, -1}, {-1, -1}, {-1, 1}};
inline bool is_diagonal_side(int side) { return side >= kDiagonal; }
template <typename Site>
int segment_side(const Site& s) {
  if (s.x0() == s.x1()) return s.y1() > s.y0() ? kLineRightOfIt : kLineLeftOfIt;  // up: right is +x
  if (s.y0() == s.y1()) return s.x1() > s.x0() ? kLineBelowIt : kLineAboveIt;
  // The arc on the right of d = point1 - point0: the line lies in direction (-dy, dx) from it.
  const bool nx = s.y1() < s.y0(), ny = s.x1() > s.x0();  // n's signs: +1 where true
  return kDiagonal + (nx ? (ny ? 0 : 1) : (ny ? 3 : 2));
}

// The sign of the cross product of (ax, ay) and (bx, by), in 128 bits.
inline int orientation128(std::int64_t ax, std::int64_t ay, std::int64_t bx, std::int64_t by) {
  const __int128 v = __int128(ax) * by - __int128(ay) * bx;
  return v > 0 ? 1 : (v < 0 ? -1 : 0);
}

// Whether a, b, c turn left (1), right (-1) or lie on a line (0).
inline int orientation(std::int64_t ax, std::int64_t ay, std::int64_t bx, std::int64_t by, std::int64_t cx,
                       std::int64_t cy) {
  return orientation128(bx - ax, by - ay, cx - ax, cy - ay);
}

// The ball of N_eps through three points, if there is one: centre, radius and the sweep
// position at which the sweep line touches it. Each point lies on one side of the ball; for
// each choice of sides the centre solves a 3x3 linear system, and it is the ball only if the
// chosen side is the outermost for each point.
struct Ball {
  Eps cx, cy, r, den;  // centre (cx, cy) / den, radius r / den; den > 0
};

// Polynomials in eps of a fixed number of terms N: the sides are linear, so every quantity of
// the solve below has a known degree, and products unroll with no test of leading zeros.
template <int N>
struct Poly {
  std::int64_t c[N];
  int sign() const {
    for (std::int64_t v : c)
      if (v != 0) return v > 0 ? 1 : -1;
    return 0;
  }
  Eps eps() const {
    Eps e;
    for (int i = 0; i < N; ++i) e.c[i] = c[i];
    return e;
  }
};
template <int N, int M>
Poly<(N > M ? N : M)> operator+(const Poly<N>& a, const Poly<M>& b) {
  Poly<(N > M ? N : M)> r{};
  for (int i = 0; i < N; ++i) r.c[i] += a.c[i];
  for (int i = 0; i < M; ++i) r.c[i] += b.c[i];
  return r;
}
template <int N>
Poly<N> operator-(const Poly<N>& a) {
  Poly<N> r;
  for (int i = 0; i < N; ++i) r.c[i] = -a.c[i];
  return r;
}
template <int N, int M>
Poly<(N > M ? N : M)> operator-(const Poly<N>& a, const Poly<M>& b) {
  return a + -b;
}
template <int N, int M>
Poly<N + M - 1> operator*(const Poly<N>& a, const Poly<M>& b) {
  Poly<N + M - 1> r{};
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < M; ++j) r.c[i + j] += a.c[i] * b.c[j];
  return r;
}
using Lin = Poly<2>;
inline Lin alpha_of(int k) { return {{kAlpha[k][0], kAlpha[k][1]}}; }
inline Lin beta_of(int k) { return {{kBeta[k][0], kBeta[k][1]}}; }

// alpha_i beta_j - alpha_j beta_i, the 2x2 minors of two sides, from a table.
inline const Poly<3>& minor_of(int i, int j) {
  static const auto m = [] {
    std::array<Poly<3>, kSides * kSides> t{};
    for (int a = 0; a < kSides; ++a)
      for (int b = 0; b < kSides; ++b) t[a * kSides + b] = alpha_of(a) * beta_of(b) - alpha_of(b) * beta_of(a);
    return t;
  }();
  return m[i * kSides + j];
}

// The ball for sides side[0..2] of the three sites (anchors x, y: a point site, or a point of
// a segment's line, whose side is one of the line forms 8..15), if each point's side is the
// outermost at its centre. Rows (alpha, beta, gamma) . (cx, cy, r) = alpha x + beta y, by
// Cramer's rule through the 2x2 minors of the sides (the third column is constant: -1, or -2
// for a 45-degree line): d and the centre are quadratic in eps, the radius cubic.
inline bool ball_on_sides(const std::int64_t x[3], const std::int64_t y[3], const int side[3], Ball& out) {
  const Lin a1 = alpha_of(side[0]), b1 = beta_of(side[0]), a2 = alpha_of(side[1]), b2 = beta_of(side[1]),
            a3 = alpha_of(side[2]), b3 = beta_of(side[2]);
  const Poly<3>&m12 = minor_of(side[0], side[1]), &m13 = minor_of(side[0], side[2]), &m23 = minor_of(side[1], side[2]);
  auto c = [](std::int64_t v) { return Poly<1>{{v}}; };
  const Lin h1 = a1 * c(x[0]) + b1 * c(y[0]), h2 = a2 * c(x[1]) + b2 * c(y[1]), h3 = a3 * c(x[2]) + b3 * c(y[2]);
  Poly<3> d, cx, cy;
  Poly<4> r = h1 * m23 - h2 * m13 + h3 * m12;
  const std::int64_t g1 = kGamma[side[0]], g2 = kGamma[side[1]], g3 = kGamma[side[2]];
  if (g1 == -1 && g2 == -1 && g3 == -1) {  // no 45-degree line: the usual case, shorter
    d = m13 - m12 - m23;
    cx = h1 * (b3 - b2) + h2 * (b1 - b3) + h3 * (b2 - b1);
    cy = h1 * (a2 - a3) + h2 * (a3 - a1) + h3 * (a1 - a2);
  } else {
    d = c(g3) * m12 - c(g2) * m13 + c(g1) * m23;
    cx = h1 * (b2 * c(g3) - b3 * c(g2)) - b1 * (h2 * c(g3) - h3 * c(g2)) + c(g1) * (h2 * b3 - h3 * b2);
    cy = a1 * (h2 * c(g3) - h3 * c(g2)) - h1 * (a2 * c(g3) - a3 * c(g2)) + c(g1) * (a2 * h3 - a3 * h2);
  }
  const int ds = d.sign();
  if (ds == 0) return false;
  if (ds < 0) d = -d, cx = -cx, cy = -cy, r = -r;
  if (r.sign() < 0) return false;  // radius 0: a corner, where two edges meet their common end
  for (int a = 0; a < 3; ++a) {
    if (side[a] >= 8) continue;  // a line: touched by construction
    const Poly<3> u = cx - c(x[a]) * d, v = cy - c(y[a]) * d;
    for (int k = 0; k < 8; ++k) {
      if (k == side[a]) continue;
      // At eps = 0 a side's form is +-u or +-v: strictly below r there, it is below r.
      const std::int64_t v0 = k < 4 ? (k < 2 ? u.c[0] : -u.c[0]) : (k < 6 ? v.c[0] : -v.c[0]);
      if (v0 < r.c[0]) continue;
      if ((alpha_of(k) * u + beta_of(k) * v - r).sign() > 0) return false;
    }
  }
  out.cx = cx.eps(), out.cy = cy.eps(), out.r = r.eps(), out.den = d.eps();
  return true;
}

// The L-inf squares (eps = 0) through the three points that hold two of them on opposite
// sides: every square through three points does, unless two share a side (a continuum of
// squares, whose ends are again such squares). Opposite sides fix the square's side and its
// centre along that axis; the third point, on a perpendicular side, fixes the rest. Centres
// and half sides in doubles (halves of integers: exact); `f(cx, cy, r)` for each.
template <typename F>
void squares_through(const std::int64_t x[3], const std::int64_t y[3], F f) {
  for (int third = 0; third < 3; ++third) {
    const int i = (third + 1) % 3, j = (third + 2) % 3;
    for (int axis = 0; axis < 2; ++axis) {
      const std::int64_t* a = axis == 0 ? x : y;  // the pair's axis
      const std::int64_t* b = axis == 0 ? y : x;
      const std::int64_t lo = std::min(a[i], a[j]), hi = std::max(a[i], a[j]);
      if (hi == lo) continue;
      const double h = 0.5 * double(hi - lo), ca = 0.5 * double(hi + lo);
      if (std::fabs(double(a[third]) - ca) > h) continue;
      for (int dir = -1; dir <= 1; dir += 2) {
        const double cb = double(b[third]) - dir * h;  // the third on the side facing dir
        if (std::fabs(double(b[i]) - cb) > h || std::fabs(double(b[j]) - cb) > h) continue;
        if (axis == 0) f(ca, cb, h);
        else f(cb, ca, h);
      }
    }
  }
}

// The sides of N_eps a point lies on at an L-inf square, from the centre's offset (u, v) and the
// half side m: both eps sides of each L-inf side the point is on into cand; into pref only the
// one its minor coordinate picks (side 0, (1 + eps) u + eps v, is outermost where v > 0), or
// both where that coordinate is 0. At an isolated square pref holds the ball's sides; where the
// ball's limit lies inside an edge of a continuum of squares the sign may differ, so pref is an
// order of trial, never a restriction.
template <typename T>
void sides_at(T u, T v, T m, unsigned& cand, unsigned& pref) {
  auto minor = [](T w, unsigned plus, unsigned minus) { return w > 0 ? plus : (w < 0 ? minus : plus | minus); };
  if (u == m) cand |= 0x03u, pref |= minor(v, 0x01u, 0x02u);
  if (-u == m) cand |= 0x0cu, pref |= minor(v, 0x04u, 0x08u);
  if (v == m) cand |= 0x30u, pref |= minor(u, 0x10u, 0x20u);
  if (-v == m) cand |= 0xc0u, pref |= minor(u, 0x40u, 0x80u);
}

// The L-inf square (eps = 0) with each of three sites on a given side: rows (a, b, g) .
// (cx, cy, r) = h, a side's form (a, b) being +-x or +-y (g = -1) or a 45-degree line's
// -(+-x +- y) (g = -2), and h = a x + b y its site's anchor. Centre (cx, cy) / d and half side
// r / d, d > 0; false if the three are dependent. Exact in int64 for coordinates within
// +-2^30 (|d| <= 24).
struct Square {
  std::int64_t cx, cy, r, d;
};
inline bool square_on(const std::int64_t a[3], const std::int64_t b[3], const std::int64_t g[3], const std::int64_t h[3],
                      Square& q) {
  const std::int64_t m12 = a[0] * b[1] - a[1] * b[0], m13 = a[0] * b[2] - a[2] * b[0], m23 = a[1] * b[2] - a[2] * b[1];
  q.d = g[2] * m12 - g[1] * m13 + g[0] * m23;
  if (q.d == 0) return false;
  q.cx = h[0] * (b[1] * g[2] - b[2] * g[1]) - b[0] * (h[1] * g[2] - h[2] * g[1]) + g[0] * (h[1] * b[2] - h[2] * b[1]);
  q.cy = a[0] * (h[1] * g[2] - h[2] * g[1]) - h[0] * (a[1] * g[2] - a[2] * g[1]) + g[0] * (a[1] * h[2] - a[2] * h[1]);
  q.r = h[0] * m23 - h[1] * m13 + h[2] * m12;
  if (q.d < 0) q.d = -q.d, q.cx = -q.cx, q.cy = -q.cy, q.r = -q.r;
  return true;
}

// Every vertex of the set of L-inf squares through the three sites (a point on a side of the
// square, a segment's line on the side facing it): three independent conditions, each "point
// a on side s" (up to two a point, at a corner) or a line's (every line's among them), met by
// a square that holds all the points. The bits of the sides each point lies on at some vertex
// are or-ed into cand and pref (sides_at).
inline bool square_vertex_sides(const std::int64_t x[3], const std::int64_t y[3], const int fixed[3], unsigned cand[3],
                                unsigned pref[3]) {
  std::int64_t A[15], B[15], G[15], H[15];  // the conditions: the lines' first, then each point's four
  int n = 0, lines = 0;
  auto add = [&](int site, int side) {
    A[n] = kAlpha[side][0], B[n] = kBeta[side][0], G[n] = kGamma[side], H[n] = A[n] * x[site] + B[n] * y[site], ++n;
  };
  for (int s = 0; s < 3; ++s)
    if (fixed[s] >= 0) add(s, fixed[s]), ++lines;
  for (int s = 0; s < 3; ++s)
    if (fixed[s] < 0)
      for (int sd = 0; sd < 8; sd += 2) add(s, sd);  // u = r, -u = r, v = r, -v = r
  bool any = false;
  for (int c1 = 0; c1 < (lines >= 1 ? 1 : n); ++c1)
    for (int c2 = c1 + 1; c2 < (lines >= 2 ? 2 : n); ++c2)
      for (int c3 = c2 + 1; c3 < (lines >= 3 ? 3 : n); ++c3) {
        const std::int64_t a[3] = {A[c1], A[c2], A[c3]}, b[3] = {B[c1], B[c2], B[c3]}, g[3] = {G[c1], G[c2], G[c3]},
                           h[3] = {H[c1], H[c2], H[c3]};
        Square q;
        if (!square_on(a, b, g, h, q) || q.r < 0) continue;
        bool ok = true;
        for (int s = 0; s < 3 && ok; ++s)
          if (fixed[s] < 0) ok = std::max(std::llabs(q.cx - x[s] * q.d), std::llabs(q.cy - y[s] * q.d)) == q.r;
        if (!ok) continue;
        any = true;
        for (int s = 0; s < 3; ++s)
          if (fixed[s] < 0) sides_at<std::int64_t>(q.cx - x[s] * q.d, q.cy - y[s] * q.d, q.r, cand[s], pref[s]);
      }
  return any;
}

// Where a ball touches a segment's line: its centre's x (a horizontal line) or y (a vertical
// one), or for a 45-degree line the x of its diagonal vertex, c + r n / (1 + 2 eps), must lie
// within the segment's closed span [lo, hi] (of x, or of y for a vertical one), or the ball
// touches the line beside the segment.
struct Span {
  std::int64_t lo = 0, hi = -1;  // empty: a point site
};
inline bool touches_within(const Ball& b, int side, const Span& sp) {
  if (sp.hi < sp.lo) return true;
  if (is_diagonal_side(side)) {  // x (1 + 2 eps) den = cx (1 + 2 eps) + n_x r
    const Eps k = Eps::of(1, 2), at = b.cx * k + kDiagonalN[side - kDiagonal][0] * b.r, den = b.den * k;
    return (at - sp.lo * den).sign() >= 0 && (sp.hi * den - at).sign() >= 0;
  }
  const Eps& c = (side == kLineBelowIt || side == kLineAboveIt) ? b.cx : b.cy;
  // The constant terms decide unless they tie.
  const std::int64_t lo0 = c.c[0] - sp.lo * b.den.c[0], hi0 = sp.hi * b.den.c[0] - c.c[0];
  if (lo0 != 0 && hi0 != 0) return lo0 > 0 && hi0 > 0;
  return (c - sp.lo * b.den).sign() >= 0 && (sp.hi * b.den - c).sign() >= 0;
}

// A filter ahead of the exact solve, on the constant terms alone (the L-inf square the ball
// tends to): where that system is regular its solution is the constant term of the exact one,
// so what fails strictly there fails for every small eps: a negative radius, a side outside
// the square, with spans a centre beyond a segment's span or a left turn (touches_within,
// turns_left). Most choices end here, in a few int64 operations instead of cubic polynomials.
// False only if the exact tests would be.
inline bool limit_may_hold(const std::int64_t x[3], const std::int64_t y[3], const int side[3], const Span* spans) {
  std::int64_t al[3], be[3], ga[3], h[3];
  for (int s = 0; s < 3; ++s)
    al[s] = kAlpha[side[s]][0], be[s] = kBeta[side[s]][0], ga[s] = kGamma[side[s]], h[s] = al[s] * x[s] + be[s] * y[s];
  Square q;
  if (!square_on(al, be, ga, h, q)) return true;  // singular at eps = 0: only the higher orders decide
  const std::int64_t cx = q.cx, cy = q.cy, r = q.r, d = q.d;
  if (r < 0) return false;
  std::int64_t tx[3], ty[3];  // where the square touches each site, times d
  for (int a = 0; a < 3; ++a) {
    tx[a] = x[a] * d, ty[a] = y[a] * d;
    if (side[a] < 8) {
      const std::int64_t u = cx - tx[a], v = cy - ty[a];
      if (std::max(std::max(u, -u), std::max(v, -v)) > r) return false;
      continue;
    }
    if (is_diagonal_side(side[a])) {  // the square's corner towards the line
      tx[a] = cx + kDiagonalN[side[a] - kDiagonal][0] * r, ty[a] = cy + kDiagonalN[side[a] - kDiagonal][1] * r;
      if (spans && spans[a].lo <= spans[a].hi && (tx[a] < spans[a].lo * d || tx[a] > spans[a].hi * d)) return false;
      continue;
    }
    const bool horizontal_line = side[a] == kLineBelowIt || side[a] == kLineAboveIt;
    std::int64_t& along = horizontal_line ? tx[a] : ty[a];
    along = horizontal_line ? cx : cy;
    if (spans && spans[a].lo <= spans[a].hi && (along < spans[a].lo * d || along > spans[a].hi * d)) return false;
  }
  return !spans || orientation128(tx[1] - tx[0], ty[1] - ty[0], tx[2] - tx[0], ty[2] - ty[0]) <= 0;
}

// Whether the ball meets the three sites counter-clockwise (bottom arc, middle, top): where
// it touches a point is the point, a horizontal line (cx, y0), a vertical one (x0, cy), a
// 45-degree one its diagonal vertex c + r n / (1 + 2 eps). An event whose middle arc vanishes
// meets them clockwise (as the three points of Boost's point case must turn); touches that
// coincide (a corner, an edge at its own end) decide nothing.
inline bool turns_left(const std::int64_t x[3], const std::int64_t y[3], const int side[3], const Ball& b) {
  std::int64_t lx[3], ly[3];  // the constant terms first: they decide unless they tie
  bool diagonal = false;
  for (int a = 0; a < 3; ++a) {
    if (is_diagonal_side(side[a])) {
      const std::int64_t* n = kDiagonalN[side[a] - kDiagonal];
      lx[a] = b.cx.c[0] + n[0] * b.r.c[0], ly[a] = b.cy.c[0] + n[1] * b.r.c[0], diagonal = true;
      continue;
    }
    lx[a] = side[a] == kLineBelowIt || side[a] == kLineAboveIt ? b.cx.c[0] : x[a] * b.den.c[0];
    ly[a] = side[a] == kLineLeftOfIt || side[a] == kLineRightOfIt ? b.cy.c[0] : y[a] * b.den.c[0];
  }
  const int turn = orientation128(lx[1] - lx[0], ly[1] - ly[0], lx[2] - lx[0], ly[2] - ly[0]);
  if (turn != 0) return turn > 0;
  Eps tx[3], ty[3];  // times den, and (1 + 2 eps) with a 45-degree line among them
  const Eps k = Eps::of(1, 2);
  for (int a = 0; a < 3; ++a) {
    if (is_diagonal_side(side[a])) {
      const std::int64_t* n = kDiagonalN[side[a] - kDiagonal];
      tx[a] = b.cx * k + n[0] * b.r, ty[a] = b.cy * k + n[1] * b.r;
      continue;
    }
    const bool horizontal_line = side[a] == kLineBelowIt || side[a] == kLineAboveIt;
    const bool vertical_line = side[a] == kLineLeftOfIt || side[a] == kLineRightOfIt;
    tx[a] = horizontal_line ? b.cx : x[a] * b.den;
    ty[a] = vertical_line ? b.cy : y[a] * b.den;
    if (diagonal) tx[a] = tx[a] * k, ty[a] = ty[a] * k;
  }
  return sign_of_cross(tx[1] - tx[0], ty[1] - ty[0], tx[2] - tx[0], ty[2] - ty[0]) > 0;
}

// The first choice of sides among the candidates (bit k of cand[a]: side k for site a) that
// gives a ball touching the segments within their spans; the choices within pref first, none
// within skip (already tried).
inline bool ball_among(const std::int64_t x[3], const std::int64_t y[3], const unsigned cand[3], Ball& out,
                       const Span* spans = nullptr, const unsigned* pref = nullptr, const unsigned* skip = nullptr) {
  auto within = [](const unsigned* m, int i, int j, int k) { return m && (m[0] >> i & m[1] >> j & m[2] >> k & 1u); };
  for (int pass = pref ? 0 : 1; pass < 2; ++pass) {
    const unsigned* bits = pass == 0 ? pref : cand;
    for (unsigned mi = bits[0]; mi; mi &= mi - 1)
      for (unsigned mj = bits[1]; mj; mj &= mj - 1)
        for (unsigned mk = bits[2]; mk; mk &= mk - 1) {
          const int i = __builtin_ctz(mi), j = __builtin_ctz(mj), k = __builtin_ctz(mk);
          if ((pass == 1 && within(pref, i, j, k)) || within(skip, i, j, k)) continue;
          const int side[3] = {i, j, k};
          if (!limit_may_hold(x, y, side, spans) || !ball_on_sides(x, y, side, out)) continue;
          if (spans && !(touches_within(out, i, spans[0]) && touches_within(out, j, spans[1]) &&
                         touches_within(out, k, spans[2])))
            continue;
          if (spans && turns_left(x, y, side, out)) continue;
          return true;
        }
  }
  return false;
}

// Why the vertices' sides are enough (ball_through, ball_touching). As eps -> 0 the ball
// tends to an L-inf square on which each point lies on the L-inf side that its N_eps side
// tends to (sides 0 and 1 to u = r, ...), each line touched from its side. Fix those sides:
// the squares meeting them are a polyhedron in (cx, cy, r) (the points' equalities and lines,
// a point's minor coordinate within [-r, r]), and with a point among the sites it holds no
// line (those bounds pin every direction), so the smallest face holding the limit square has
// a vertex. There the same equalities hold, each of three independent ones "a point on a
// side" or a line's (all lines among them: parallel lines are independent): the vertices that
// square_vertex_sides enumerates. Three lines alone meet in one square or none. So each
// point's limit side is among the sides it lies on at some vertex, and both eps sides of each
// are candidates: if no choice among them gives the ball, no choice does.

// The ball of N_eps through three points, with a radius that stays finite as eps -> 0 (one
// that does not meets the sweep line beyond every finite event: the limit diagram has two
// parallel rays there, no vertex). The candidates are the sides at the vertices of the set of
// L-inf squares through the points (above); the squares squares_through finds (two points on
// opposite sides) are most often such vertices and cheaper, so they are tried first.
inline bool ball_through(const std::int64_t x[3], const std::int64_t y[3], Ball& out) {
  unsigned cand[3] = {0, 0, 0}, pref[3] = {0, 0, 0};
  bool any = false;
  squares_through(x, y, [&](double cx, double cy, double) {
    any = true;
    for (int a = 0; a < 3; ++a) {
      const double u = cx - double(x[a]), v = cy - double(y[a]);
      sides_at(u, v, std::max(std::fabs(u), std::fabs(v)), cand[a], pref[a]);
    }
  });
  if (!any) return false;
  if (ball_among(x, y, cand, out, nullptr, pref)) return true;
  const unsigned first[3] = {cand[0], cand[1], cand[2]};
  const int none[3] = {-1, -1, -1};
  square_vertex_sides(x, y, none, cand, pref);
  // The choices already tried are first's: the new ones have a side outside it.
  return (cand[0] != first[0] || cand[1] != first[1] || cand[2] != first[2]) &&
         ball_among(x, y, cand, out, nullptr, nullptr, first);
}

// The ball touching three sites of which some are segments (fixed[a]: the side of its line
// the segment's arc faces, or -1 for a point; x, y: the point, or the segment's point0), at a
// point of each segment (spans). The candidates: the sides at the vertices (above).
inline bool ball_touching(const std::int64_t x[3], const std::int64_t y[3], const int fixed[3], const Span spans[3],
                          Ball& out) {
  unsigned cand[3] = {0, 0, 0};
  for (int a = 0; a < 3; ++a)
    if (fixed[a] >= 0) cand[a] = 1u << fixed[a];
  unsigned pref[3] = {cand[0], cand[1], cand[2]};
  if (!square_vertex_sides(x, y, fixed, cand, pref)) return false;
  return ball_among(x, y, cand, out, spans, pref);
}

}  // namespace linf::sweep
