// The balls of the sweep's circle events: a ball of N_eps = L-inf + eps L1 (eps.hpp) touching
// three sites, each point on one of the octagon's sides, each segment's line from the side its
// arc faces. The sides are found from the L-inf squares (eps = 0) through the
// sites; for each choice the centre solves a 3x3 linear system, exactly.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <type_traits>

#include "diagram/sweep/eps.hpp"

namespace linf::sweep {

// The eight sides of N_eps's unit ball, (alpha, beta) as c0 + c1 eps: N_eps(u, v) is the
// largest of alpha u + beta v. Then a segment's line touched by the ball: an axis-parallel one
// (N_eps of a point's distance to it is (1 + eps) times the L-inf one) with the ball left of
// (below, right of, above) it, sides 8-11; a slanted one (neither axis-parallel: 45 degrees or
// any other slope), sides 12-15, lying in direction n from the ball, the quadrant of n being
// (1, 1), (1, -1), (-1, -1), (-1, 1). N_eps's ball reaches a line of normal n first at the
// octagon's diagonal vertex (+-1, +-1) / (1 + 2 eps) (the support (|n_x| + |n_y|) / (1 + 2 eps)
// beats max(|n_x|, |n_y|) / (1 + eps) for every small eps unless n is axis-parallel): its row is
// -(1 + 2 eps) n . (c - p) = (|n_x| + |n_y|) r, its radius column -(|n_x| + |n_y|) (-2 at 45
// degrees, where n = (+-1, +-1)); the other sides' is -1. A slanted side's row needs its normal
// (Normal): rows of sides 12-15 come from row_of, never from the tables.
constexpr std::int64_t kAlpha[12][2] = {{1, 1},  {1, 1},   {-1, -1}, {-1, -1},  // x dominant, right; left
                                        {0, 1},  {0, -1},  {0, 1},   {0, -1},   // y dominant, up; down
                                        {-1, -1}, {0, 0},  {1, 1},   {0, 0}};   // axis-parallel lines
constexpr std::int64_t kBeta[12][2] = {{0, 1},  {0, -1},  {0, 1},   {0, -1},
                                       {1, 1},  {1, 1},   {-1, -1}, {-1, -1},
                                       {0, 0},  {-1, -1}, {0, 0},   {1, 1}};
constexpr int kSides = 16;
template <typename I>
struct SideT {
  EpsT<I> alpha, beta;
};
// The point sides 0-7 as polynomials.
template <typename I>
const SideT<I>* sides() {
  static const auto s = [] {
    std::array<SideT<I>, 8> t;
    for (int k = 0; k < 8; ++k)
      t[k] = {EpsT<I>::of(I(kAlpha[k][0]), I(kAlpha[k][1])), EpsT<I>::of(I(kBeta[k][0]), I(kBeta[k][1]))};
    return t;
  }();
  return s.data();
}
// Side 8 + segment_side(...): the side of a segment's line that its arc (Boost's site event,
// possibly inverted) lies on: the right of point0 -> point1.
constexpr int kLineLeftOfIt = 8, kLineBelowIt = 9, kLineRightOfIt = 10, kLineAboveIt = 11;
constexpr int kDiagonal = 12;  // 12 + k: a slanted line, its normal in quadrant kDiagonalN[k]
constexpr std::int64_t kDiagonalN[4][2] = {{1, 1}, {1, -1}, {-1, -1}, {-1, 1}};
inline bool is_diagonal_side(int side) { return side >= kDiagonal; }

// A slanted segment's normal n = (-dy, dx) / gcd for d = point1 - point0: towards the line
// from its arc's side (the right of d). (+-1, +-1) at 45 degrees; zero for a point or an
// axis-parallel segment (their rows are the tables').
struct Normal {
  std::int64_t x = 0, y = 0;
  std::int64_t l1() const { return (x < 0 ? -x : x) + (y < 0 ? -y : y); }
};
inline std::int64_t gcd64(std::int64_t a, std::int64_t b) {
  a = a < 0 ? -a : a, b = b < 0 ? -b : b;
  while (b) a %= b, std::swap(a, b);
  return a;
}
template <typename Site>
Normal segment_normal(const Site& s) {
  const std::int64_t dx = std::int64_t(s.x1()) - s.x0(), dy = std::int64_t(s.y1()) - s.y0();
  if (dx == 0 || dy == 0) return {};
  const std::int64_t g = gcd64(dx, dy);
  return {-dy / g, dx / g};
}
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
template <typename W>
int orientation_wide(const W& ax, const W& ay, const W& bx, const W& by) {
  if constexpr (!std::is_same_v<W, __int128>) {
    const int f = filtered_sign(ax, by, ay, bx);
    if (f != 0) return f;
  }
  const W l = ax * by, r = ay * bx;
  return l > r ? 1 : (l < r ? -1 : 0);
}

// Whether a, b, c turn left (1), right (-1) or lie on a line (0).
inline int orientation(std::int64_t ax, std::int64_t ay, std::int64_t bx, std::int64_t by, std::int64_t cx,
                       std::int64_t cy) {
  return orientation128(bx - ax, by - ay, cx - ax, cy - ay);
}

// The ball of N_eps through three sites, if there is one: centre, radius and the sweep
// position at which the sweep line touches it. Each point lies on one side of the ball; for
// each choice of sides the centre solves a 3x3 linear system, and it is the ball only if the
// chosen side is the outermost for each point.
template <typename I>
struct BallT {
  EpsT<I> cx, cy, r, den;  // centre (cx, cy) / den, radius r / den; den > 0
};
using Ball = BallT<std::int64_t>;

// Polynomials in eps of a fixed number of terms N: the sides are linear, so every quantity of
// the solve below has a known degree, and products unroll with no test of leading zeros.
template <typename I, int N>
struct Poly {
  I c[N];
  int sign() const {
    for (const I& v : c)
      if (v != 0) return v > 0 ? 1 : -1;
    return 0;
  }
  EpsT<I> eps() const {
    EpsT<I> e;
    for (int i = 0; i < N; ++i) e.c[i] = c[i];
    return e;
  }
};
template <typename I, int N, int M>
Poly<I, (N > M ? N : M)> operator+(const Poly<I, N>& a, const Poly<I, M>& b) {
  Poly<I, (N > M ? N : M)> r{};
  for (int i = 0; i < N; ++i) r.c[i] += a.c[i];
  for (int i = 0; i < M; ++i) r.c[i] += b.c[i];
  return r;
}
template <typename I, int N>
Poly<I, N> operator-(const Poly<I, N>& a) {
  Poly<I, N> r;
  for (int i = 0; i < N; ++i) r.c[i] = -a.c[i];
  return r;
}
template <typename I, int N, int M>
Poly<I, (N > M ? N : M)> operator-(const Poly<I, N>& a, const Poly<I, M>& b) {
  return a + -b;
}
template <typename I, int N, int M>
Poly<I, N + M - 1> operator*(const Poly<I, N>& a, const Poly<I, M>& b) {
  Poly<I, N + M - 1> r{};
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < M; ++j) r.c[i + j] += a.c[i] * b.c[j];
  return r;
}
template <typename I>
using Lin = Poly<I, 2>;
template <typename I>
Lin<I> alpha_of(int k) {
  return {{I(kAlpha[k][0]), I(kAlpha[k][1])}};
}
template <typename I>
Lin<I> beta_of(int k) {
  return {{I(kBeta[k][0]), I(kBeta[k][1])}};
}

// A side's row: (alpha, beta, gamma) . (cx, cy, r) = alpha x + beta y.
template <typename I>
struct Row {
  Lin<I> alpha, beta;
  I gamma;
};
template <typename I>
Row<I> row_of(int side, const Normal& n) {
  if (side < kDiagonal) return {alpha_of<I>(side), beta_of<I>(side), I(-1)};
  return {{{I(-n.x), I(-2 * n.x)}}, {{I(-n.y), I(-2 * n.y)}}, I(-n.l1())};
}

// alpha_i beta_j - alpha_j beta_i, the 2x2 minors of two of the sides 0-11, from a table.
inline const Poly<std::int64_t, 3>& minor_of(int i, int j) {
  using I = std::int64_t;
  static const auto m = [] {
    std::array<Poly<I, 3>, kDiagonal * kDiagonal> t{};
    for (int a = 0; a < kDiagonal; ++a)
      for (int b = 0; b < kDiagonal; ++b) t[a * kDiagonal + b] = alpha_of<I>(a) * beta_of<I>(b) - alpha_of<I>(b) * beta_of<I>(a);
    return t;
  }();
  return m[i * kDiagonal + j];
}
template <typename I>
Poly<I, 3> minor(int i, int j, const Row<I>& ri, const Row<I>& rj) {
  if (i >= kDiagonal || j >= kDiagonal) return ri.alpha * rj.beta - rj.alpha * ri.beta;
  const Poly<std::int64_t, 3>& m = minor_of(i, j);
  return {{I(m.c[0]), I(m.c[1]), I(m.c[2])}};
}

// The ball for sides side[0..2] of the three sites (anchors x, y: a point site, or a point of
// a segment's line, whose side is one of the line forms 8..15, a slanted one with its normal
// nrm[a]), if each point's side is the outermost at its centre. Rows (alpha, beta, gamma) .
// (cx, cy, r) = alpha x + beta y, by Cramer's rule through the 2x2 minors of the sides: d and
// the centre are quadratic in eps, the radius cubic. Bounds (coordinates within +-2^30, a
// normal's entries within 2^31): alpha, beta within 2^32, gamma 2^32, the anchors' forms
// 2^63, minors 2^66, d 2^100, the centre and the radius 2^131.
template <typename I>
bool ball_on_sides(const std::int64_t x[3], const std::int64_t y[3], const int side[3], const Normal* nrm,
                   BallT<I>& out) {
  static const Normal none;
  const Row<I> r1 = row_of<I>(side[0], nrm ? nrm[0] : none), r2 = row_of<I>(side[1], nrm ? nrm[1] : none),
               r3 = row_of<I>(side[2], nrm ? nrm[2] : none);
  const Lin<I>&a1 = r1.alpha, &b1 = r1.beta, &a2 = r2.alpha, &b2 = r2.beta, &a3 = r3.alpha, &b3 = r3.beta;
  const Poly<I, 3> m12 = minor(side[0], side[1], r1, r2), m13 = minor(side[0], side[2], r1, r3),
                   m23 = minor(side[1], side[2], r2, r3);
  auto c = [](const I& v) { return Poly<I, 1>{{v}}; };
  const Lin<I> h1 = a1 * c(I(x[0])) + b1 * c(I(y[0])), h2 = a2 * c(I(x[1])) + b2 * c(I(y[1])),
               h3 = a3 * c(I(x[2])) + b3 * c(I(y[2]));
  Poly<I, 3> d, cx, cy;
  Poly<I, 4> r = h1 * m23 - h2 * m13 + h3 * m12;
  const I &g1 = r1.gamma, &g2 = r2.gamma, &g3 = r3.gamma;
  if (g1 == -1 && g2 == -1 && g3 == -1) {  // no slanted line: the usual case, shorter
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
    const Poly<I, 3> u = cx - c(I(x[a])) * d, v = cy - c(I(y[a])) * d;
    for (int k = 0; k < 8; ++k) {
      if (k == side[a]) continue;
      // At eps = 0 a side's form is +-u or +-v: strictly below r there, it is below r.
      const I v0 = k < 4 ? (k < 2 ? u.c[0] : I(-u.c[0])) : (k < 6 ? v.c[0] : I(-v.c[0]));
      if (v0 < r.c[0]) continue;
      if ((alpha_of<I>(k) * u + beta_of<I>(k) * v - r).sign() > 0) return false;
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
// (cx, cy, r) = h, a side's form (a, b) being +-x or +-y (g = -1) or a slanted line's -n
// (g = -(|n_x| + |n_y|)), and h = a x + b y its site's anchor. Centre (cx, cy) / d and half
// side r / d, d > 0; false if the three are dependent. Exact in I: within int64 for points,
// axis-parallel and 45-degree lines and coordinates within +-2^30 (|d| <= 24); a slanted
// line's normal makes d up to 2^98 and the rest 2^127.
template <typename I>
struct SquareT {
  I cx, cy, r, d;
};
template <typename I>
bool square_on(const I a[3], const I b[3], const I g[3], const I h[3], SquareT<I>& q) {
  const I m12 = a[0] * b[1] - a[1] * b[0], m13 = a[0] * b[2] - a[2] * b[0], m23 = a[1] * b[2] - a[2] * b[1];
  q.d = g[2] * m12 - g[1] * m13 + g[0] * m23;
  if (q.d == 0) return false;
  q.cx = h[0] * (b[1] * g[2] - b[2] * g[1]) - b[0] * (h[1] * g[2] - h[2] * g[1]) + g[0] * (h[1] * b[2] - h[2] * b[1]);
  q.cy = a[0] * (h[1] * g[2] - h[2] * g[1]) - h[0] * (a[1] * g[2] - a[2] * g[1]) + g[0] * (a[1] * h[2] - a[2] * h[1]);
  q.r = h[0] * m23 - h[1] * m13 + h[2] * m12;
  if (q.d < 0) q.d = -q.d, q.cx = -q.cx, q.cy = -q.cy, q.r = -q.r;
  return true;
}
template <typename I>
I abs_of(const I& v) {
  return v < 0 ? I(-v) : v;
}
// A side's row at eps = 0 (its constant terms).
template <typename I>
void limit_row(int side, const Normal& n, std::int64_t x, std::int64_t y, I& a, I& b, I& g, I& h) {
  if (side < kDiagonal) a = I(kAlpha[side][0]), b = I(kBeta[side][0]), g = I(-1);
  else a = I(-n.x), b = I(-n.y), g = I(-n.l1());
  h = a * I(x) + b * I(y);
}

// Every vertex of the set of L-inf squares through the three sites (a point on a side of the
// square, a segment's line on the side facing it): three independent conditions, each "point
// a on side s" (up to two a point, at a corner) or a line's (every line's among them), met by
// a square that holds all the points. The bits of the sides each point lies on at some vertex
// are or-ed into cand and pref (sides_at).
template <typename I>
bool square_vertex_sides(const std::int64_t x[3], const std::int64_t y[3], const int fixed[3], const Normal* nrm,
                         unsigned cand[3], unsigned pref[3]) {
  I A[15], B[15], G[15], H[15];  // the conditions: the lines' first, then each point's four
  int n = 0, lines = 0;
  static const Normal none;
  auto add = [&](int site, int side) {
    limit_row<I>(side, nrm ? nrm[site] : none, x[site], y[site], A[n], B[n], G[n], H[n]);
    ++n;
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
        const I a[3] = {A[c1], A[c2], A[c3]}, b[3] = {B[c1], B[c2], B[c3]}, g[3] = {G[c1], G[c2], G[c3]},
                h[3] = {H[c1], H[c2], H[c3]};
        SquareT<I> q;
        if (!square_on(a, b, g, h, q) || q.r < 0) continue;
        bool ok = true;
        for (int s = 0; s < 3 && ok; ++s)
          if (fixed[s] < 0) ok = std::max(abs_of<I>(q.cx - I(x[s]) * q.d), abs_of<I>(q.cy - I(y[s]) * q.d)) == q.r;
        if (!ok) continue;
        any = true;
        for (int s = 0; s < 3; ++s)
          if (fixed[s] < 0) sides_at<I>(q.cx - I(x[s]) * q.d, q.cy - I(y[s]) * q.d, q.r, cand[s], pref[s]);
      }
  return any;
}

// Where a ball touches a segment's line: its centre's x (a horizontal line) or y (a vertical
// one), or for a slanted line the x of its diagonal vertex, c + r sgn(n) / (1 + 2 eps), must
// lie within the segment's closed span [lo, hi] (of x, or of y for a vertical one), or the
// ball touches the line beside the segment.
struct Span {
  std::int64_t lo = 0, hi = -1;  // empty: a point site
};
template <typename I>
bool touches_within(const BallT<I>& b, int side, const Span& sp) {
  if (sp.hi < sp.lo) return true;
  if (is_diagonal_side(side)) {  // x (1 + 2 eps) den = cx (1 + 2 eps) + sgn(n_x) r
    const EpsT<I> k = EpsT<I>::of(I(1), I(2)), at = b.cx * k + I(kDiagonalN[side - kDiagonal][0]) * b.r,
                  den = b.den * k;
    return (at - I(sp.lo) * den).sign() >= 0 && (I(sp.hi) * den - at).sign() >= 0;
  }
  const EpsT<I>& c = (side == kLineBelowIt || side == kLineAboveIt) ? b.cx : b.cy;
  // The constant terms decide unless they tie.
  const I lo0 = c.c[0] - I(sp.lo) * b.den.c[0], hi0 = I(sp.hi) * b.den.c[0] - c.c[0];
  if (lo0 != 0 && hi0 != 0) return lo0 > 0 && hi0 > 0;
  return (c - I(sp.lo) * b.den).sign() >= 0 && (I(sp.hi) * b.den - c).sign() >= 0;
}

// A filter ahead of the exact solve, on the constant terms alone (the L-inf square the ball
// tends to): where that system is regular its solution is the constant term of the exact one,
// so what fails strictly there fails for every small eps: a negative radius, a side outside
// the square, with spans a centre beyond a segment's span or a left turn (touches_within,
// turns_left). Most choices end here, in a few integer operations instead of cubic
// polynomials. False only if the exact tests would be.
template <typename I>
bool limit_may_hold(const std::int64_t x[3], const std::int64_t y[3], const int side[3], const Normal* nrm,
                    const Span* spans) {
  using W = typename WideOf<I>::type;
  static const Normal none;
  I al[3], be[3], ga[3], h[3];
  for (int s = 0; s < 3; ++s) limit_row<I>(side[s], nrm ? nrm[s] : none, x[s], y[s], al[s], be[s], ga[s], h[s]);
  SquareT<I> q;
  if (!square_on(al, be, ga, h, q)) return true;  // singular at eps = 0: only the higher orders decide
  const I cx = q.cx, cy = q.cy, r = q.r, d = q.d;
  if (r < 0) return false;
  I tx[3], ty[3];  // where the square touches each site, times d
  for (int a = 0; a < 3; ++a) {
    tx[a] = I(x[a]) * d, ty[a] = I(y[a]) * d;
    if (side[a] < 8) {
      const I u = cx - tx[a], v = cy - ty[a];
      if (std::max(abs_of(u), abs_of(v)) > r) return false;
      continue;
    }
    if (is_diagonal_side(side[a])) {  // the square's corner towards the line
      tx[a] = cx + I(kDiagonalN[side[a] - kDiagonal][0]) * r, ty[a] = cy + I(kDiagonalN[side[a] - kDiagonal][1]) * r;
      if (spans && spans[a].lo <= spans[a].hi && (tx[a] < I(spans[a].lo) * d || tx[a] > I(spans[a].hi) * d)) return false;
      continue;
    }
    const bool horizontal_line = side[a] == kLineBelowIt || side[a] == kLineAboveIt;
    I& along = horizontal_line ? tx[a] : ty[a];
    along = horizontal_line ? cx : cy;
    if (spans && spans[a].lo <= spans[a].hi && (along < I(spans[a].lo) * d || along > I(spans[a].hi) * d)) return false;
  }
  return !spans || orientation_wide<W>(W(tx[1] - tx[0]), W(ty[1] - ty[0]), W(tx[2] - tx[0]), W(ty[2] - ty[0])) <= 0;
}

// Whether the ball meets the three sites counter-clockwise (bottom arc, middle, top): where
// it touches a point is the point, a horizontal line (cx, y0), a vertical one (x0, cy), a
// slanted one its diagonal vertex c + r sgn(n) / (1 + 2 eps). An event whose middle arc
// vanishes meets them clockwise (as the three points of Boost's point case must turn);
// touches that coincide (a corner, an edge at its own end) decide nothing.
template <typename I>
bool turns_left(const std::int64_t x[3], const std::int64_t y[3], const int side[3], const BallT<I>& b) {
  using W = typename WideOf<I>::type;
  I lx[3], ly[3];  // the constant terms first: they decide unless they tie
  bool diagonal = false;
  for (int a = 0; a < 3; ++a) {
    if (is_diagonal_side(side[a])) {
      const std::int64_t* n = kDiagonalN[side[a] - kDiagonal];
      lx[a] = b.cx.c[0] + I(n[0]) * b.r.c[0], ly[a] = b.cy.c[0] + I(n[1]) * b.r.c[0], diagonal = true;
      continue;
    }
    lx[a] = side[a] == kLineBelowIt || side[a] == kLineAboveIt ? b.cx.c[0] : I(x[a]) * b.den.c[0];
    ly[a] = side[a] == kLineLeftOfIt || side[a] == kLineRightOfIt ? b.cy.c[0] : I(y[a]) * b.den.c[0];
  }
  const int turn = orientation_wide<W>(W(lx[1] - lx[0]), W(ly[1] - ly[0]), W(lx[2] - lx[0]), W(ly[2] - ly[0]));
  if (turn != 0) return turn > 0;
  EpsT<I> tx[3], ty[3];  // times den, and (1 + 2 eps) with a slanted line among them
  const EpsT<I> k = EpsT<I>::of(I(1), I(2));
  for (int a = 0; a < 3; ++a) {
    if (is_diagonal_side(side[a])) {
      const std::int64_t* n = kDiagonalN[side[a] - kDiagonal];
      tx[a] = b.cx * k + I(n[0]) * b.r, ty[a] = b.cy * k + I(n[1]) * b.r;
      continue;
    }
    const bool horizontal_line = side[a] == kLineBelowIt || side[a] == kLineAboveIt;
    const bool vertical_line = side[a] == kLineLeftOfIt || side[a] == kLineRightOfIt;
    tx[a] = horizontal_line ? b.cx : I(x[a]) * b.den;
    ty[a] = vertical_line ? b.cy : I(y[a]) * b.den;
    if (diagonal) tx[a] = tx[a] * k, ty[a] = ty[a] * k;
  }
  return sign_of_cross(tx[1] - tx[0], ty[1] - ty[0], tx[2] - tx[0], ty[2] - ty[0]) > 0;
}

// Whether the ball can be the event of its middle site's arc. Near the centre each site's
// N_eps distance is linear (its side's gradient), so the three edges leave the centre as rays,
// and along a ray the sweep position q.x + d(q) grows, stays or falls. The middle arc vanishes
// there only if its edges with its neighbours come from behind the sweep (that position does
// not grow along them) and its neighbours' new edge leads ahead (it does not fall). Where one
// site's arc lies on both sides of two others (A, B, C, A from the bottom), (A, B, C) and
// (B, C, A) have one ball and turn alike: this tells which of B and C vanishes. An edge along
// which a third site ties decides nothing. Asked only where a segment is among the three (no
// point set has shown the need, and they have the most events).
template <typename I>
bool middle_may_vanish(const int side[3], const Normal* nrm) {
  // Every gradient is linear in eps and every quantity below a sum of products of two of them:
  // polynomials of degree 2, in the tier's own type. Bounds: a slanted normal's entries within
  // 2^24 in the 128-bit tier (sweep.cpp) make gradients and d within 2^25, the turned
  // differences within 2^51 and the sums of products within 2^104; within 2^31 in the 256-bit
  // tier, 2^132; (+-1, +-1) in the int64 tier, a few units. The wide type cost a fifth of a
  // layer of round pads in its products.
  using T = I;
  struct Lin {  // c0 + c1 eps
    T c0, c1;
  };
  struct Quad {  // c0 + c1 eps + c2 eps^2
    T c0, c1, c2;
    int sign() const { return c0 != 0 ? (c0 > 0 ? 1 : -1) : c1 != 0 ? (c1 > 0 ? 1 : -1) : c2 > 0 ? 1 : c2 < 0 ? -1 : 0; }
  };
  auto mul = [](const Lin& a, const Lin& b) { return Quad{a.c0 * b.c0, a.c0 * b.c1 + a.c1 * b.c0, a.c1 * b.c1}; };
  auto add = [](const Quad& a, const Quad& b) { return Quad{a.c0 + b.c0, a.c1 + b.c1, a.c2 + b.c2}; };
  auto lin = [](const T& k, const Lin& a, const T& m, const Lin& b) {  // k a - m b
    return Lin{k * a.c0 - m * b.c0, k * a.c1 - m * b.c1};
  };
  // Gradient a is g[a] / d[a], d[a] > 0: a table side's (alpha, beta), a slanted line's
  // -(1 + 2 eps) n / |n|_1.
  Lin gx[3], gy[3];
  T d[3];
  for (int a = 0; a < 3; ++a) {
    if (is_diagonal_side(side[a])) {
      const Normal& n = nrm[a];
      gx[a] = {T(-n.x), T(-2 * n.x)}, gy[a] = {T(-n.y), T(-2 * n.y)}, d[a] = T(n.l1());
    } else {
      gx[a] = {T(kAlpha[side[a]][0]), T(kAlpha[side[a]][1])};
      gy[a] = {T(kBeta[side[a]][0]), T(kBeta[side[a]][1])};
      d[a] = T(1);
    }
  }
  // The rate of the sweep position along the edge of i and j (k the third site), on the side
  // where k is farther: 1, 0 or -1, or 2 where k ties along it.
  auto rate = [&](int i, int j, int k) {
    const Lin wx = lin(d[j], gy[i], d[i], gy[j]), wy = lin(d[i], gx[j], d[j], gx[i]);  // (g_i - g_j) turned
    const int farther = add(mul(lin(d[i], gx[k], d[k], gx[i]), wx), mul(lin(d[i], gy[k], d[k], gy[i]), wy)).sign();
    if (farther == 0) return 2;
    const Lin ex{T(d[i] + gx[i].c0), T(d[i] + gx[i].c1)};  // (1 + eps) d_i + g_i's x
    return farther * add(mul(ex, wx), mul(gy[i], wy)).sign();  // ((1 + eps) e_x + g_i) . w, times d[i]
  };
  const int r12 = rate(0, 1, 2), r23 = rate(1, 2, 0), r13 = rate(0, 2, 1);
  return !(r12 == 1 || r23 == 1 || r13 == -1);
}

// Where the sweep is: the site event (its x) or the circle event (its lower x, of the tier in
// use) being processed, set by the builder's output as Boost calls it (sweep.cpp), which is
// before Boost asks for the balls of the arcs it has made neighbours. A ball whose event lies
// behind it is not theirs: in L2 three neighbouring arcs never have one, but an L-inf ball
// touching them can sit where their arcs were never all in front (several sites touching one
// ball at once, as segments from one point do). Per thread: tiles are swept side by side.
struct SweepAt {
  bool site = true;
  std::int64_t x = INT64_MIN;
};
inline SweepAt& sweep_at() {
  static thread_local SweepAt a;
  return a;
}
template <typename I>
RatioT<I>& sweep_at_circle() {
  static thread_local RatioT<I> r;
  return r;
}
// Whether ball b's event (the sweep touching its rightmost point) lies behind the sweep.
template <typename I>
bool behind_the_sweep(const BallT<I>& b) {
  const SweepAt& a = sweep_at();
  if (a.site && a.x == INT64_MIN) return false;
  if (a.site) {  // the sign of (cx - x den)(1 + eps) + r, den > 0, in the wide type (x den
                 // outgrows I): its constant term, or where that is 0 the whole polynomial
    using W = typename WideOf<I>::type;
    if constexpr (!std::is_same_v<I, std::int64_t>) {  // the constant term in long doubles first
      const long double cx = static_cast<long double>(b.cx.c[0]), r = static_cast<long double>(b.r.c[0]);
      const long double xd = static_cast<long double>(a.x) * static_cast<long double>(b.den.c[0]);
      const long double v = cx - xd + r, tol = (std::fabs(cx) + std::fabs(xd) + std::fabs(r)) * 0x1p-58L;
      if (v > tol) return false;
      if (v < -tol) return true;
    }
    const W c0 = W(b.cx.c[0]) - W(a.x) * W(b.den.c[0]) + W(b.r.c[0]);
    if (c0 != 0) return c0 < 0;
    EpsT<W> p;
    for (int k = 0; k < kTerms; ++k) p.c[k] = W(b.cx.c[k]) - W(a.x) * W(b.den.c[k]);
    p = times_one_plus_eps(p);  // cx and den are quadratic, r cubic: within kTerms
    for (int k = 0; k < kTerms; ++k) p.c[k] += W(b.r.c[k]);
    return p.sign() < 0;
  }
  return compare(RatioT<I>(times_one_plus_eps(b.cx) + b.r, times_one_plus_eps(b.den)), sweep_at_circle<I>()) < 0;
}

// Whether middle_may_vanish is asked of a ball with a segment among its sites: where its radius
// stays above 0 as eps -> 0 (at a corner, radius 0, the edges leave no room to vanish in). That
// is r's term at den's lowest order, not r's constant term: a system singular at eps = 0 (a
// continuum of L-inf squares, e.g. two segments from one point touched there and a point on a
// side) has den's and r's constant terms 0 and a finite ball all the same. A singular ball is
// not asked where a point of the three lies on a segment's line among them (the segment's own
// end, as at every polygon vertex): there the linear rates misjudge, and Manhattan layers'
// events at such ends were refused (design.md, "Where L-inf leaves Boost's Euclidean structure").
template <typename I>
bool vanishing_asked(const BallT<I>& b, const std::int64_t x[3], const std::int64_t y[3], const int side[3],
                     const Normal* nrm) {
  if (b.r.c[0] != 0) return true;
  int k = 0;
  while (k < kTerms && b.den.c[k] == 0) ++k;
  if (k == 0 || k == kTerms || b.r.c[k] == 0) return false;
  for (int a = 0; a < 3; ++a) {
    if (side[a] >= 8) continue;
    for (int s = 0; s < 3; ++s) {
      if (side[s] < 8) continue;
      const std::int64_t dx = x[a] - x[s], dy = y[a] - y[s];
      const bool on = is_diagonal_side(side[s]) ? __int128(nrm[s].x) * dx + __int128(nrm[s].y) * dy == 0
                                                : (side[s] == kLineBelowIt || side[s] == kLineAboveIt ? dy == 0 : dx == 0);
      if (on) return false;
    }
  }
  return true;
}

// The first choice of sides among the candidates (bit k of cand[a]: side k for site a) that
// gives a ball touching the segments within their spans; the choices within pref first, none
// within skip (already tried).
template <typename I>
bool ball_among(const std::int64_t x[3], const std::int64_t y[3], const unsigned cand[3], BallT<I>& out,
                const Normal* nrm = nullptr, const Span* spans = nullptr, const unsigned* pref = nullptr,
                const unsigned* skip = nullptr) {
  auto within = [](const unsigned* m, int i, int j, int k) { return m && (m[0] >> i & m[1] >> j & m[2] >> k & 1u); };
  for (int pass = pref ? 0 : 1; pass < 2; ++pass) {
    const unsigned* bits = pass == 0 ? pref : cand;
    for (unsigned mi = bits[0]; mi; mi &= mi - 1)
      for (unsigned mj = bits[1]; mj; mj &= mj - 1)
        for (unsigned mk = bits[2]; mk; mk &= mk - 1) {
          const int i = __builtin_ctz(mi), j = __builtin_ctz(mj), k = __builtin_ctz(mk);
          if ((pass == 1 && within(pref, i, j, k)) || within(skip, i, j, k)) continue;
          const int side[3] = {i, j, k};
          if (!limit_may_hold<I>(x, y, side, nrm, spans) || !ball_on_sides<I>(x, y, side, nrm, out)) continue;
          if (spans && !(touches_within(out, i, spans[0]) && touches_within(out, j, spans[1]) &&
                         touches_within(out, k, spans[2])))
            continue;
          if (spans && turns_left(x, y, side, out)) continue;
          if (spans && vanishing_asked(out, x, y, side, nrm) && !middle_may_vanish<I>(side, nrm)) continue;
          if (behind_the_sweep(out)) continue;
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
template <typename I>
bool ball_through(const std::int64_t x[3], const std::int64_t y[3], BallT<I>& out) {
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
  if (ball_among<I>(x, y, cand, out, nullptr, nullptr, pref)) return true;
  const unsigned first[3] = {cand[0], cand[1], cand[2]};
  const int none[3] = {-1, -1, -1};
  square_vertex_sides<I>(x, y, none, nullptr, cand, pref);
  // The choices already tried are first's: the new ones have a side outside it.
  return (cand[0] != first[0] || cand[1] != first[1] || cand[2] != first[2]) &&
         ball_among<I>(x, y, cand, out, nullptr, nullptr, nullptr, first);
}

// The ball touching three sites of which some are segments (fixed[a]: the side of its line
// the segment's arc faces, or -1 for a point; x, y: the point, or the segment's point0), at a
// point of each segment (spans). The candidates: the sides at the vertices (above).
template <typename I>
bool ball_touching(const std::int64_t x[3], const std::int64_t y[3], const int fixed[3], const Normal nrm[3],
                   const Span spans[3], BallT<I>& out) {
  unsigned cand[3] = {0, 0, 0};
  for (int a = 0; a < 3; ++a)
    if (fixed[a] >= 0) cand[a] = 1u << fixed[a];
  unsigned pref[3] = {cand[0], cand[1], cand[2]};
  if (!square_vertex_sides<I>(x, y, fixed, nrm, cand, pref)) return false;
  return ball_among<I>(x, y, cand, out, nrm, spans, pref);
}

}  // namespace linf::sweep
