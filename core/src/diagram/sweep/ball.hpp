// The balls of the sweep's circle events: a ball of N_eps = L-inf + eps L1 (eps.hpp) touching
// three sites, each point on one of the octagon's sides, each axis-parallel segment's line from
// the side its arc faces. The sides are found from the L-inf squares (eps = 0) through the
// sites; for each choice the centre solves a 3x3 linear system, exactly.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include "diagram/sweep/eps.hpp"

namespace linf::sweep {

// The eight sides of N_eps's unit ball: N_eps(u, v) is the largest of alpha u + beta v.
struct Side {
  Eps alpha, beta;
};
inline const Side* sides() {
  static const Side s[12] = {
      {Eps::of(1, 1), Eps::of(0, 1)},  {Eps::of(1, 1), Eps::of(0, -1)},   // x dominant, right
      {Eps::of(-1, -1), Eps::of(0, 1)}, {Eps::of(-1, -1), Eps::of(0, -1)},  // x dominant, left
      {Eps::of(0, 1), Eps::of(1, 1)},  {Eps::of(0, -1), Eps::of(1, 1)},    // y dominant, up
      {Eps::of(0, 1), Eps::of(-1, -1)}, {Eps::of(0, -1), Eps::of(-1, -1)},  // y dominant, down
      // A segment's line touched by the ball (N_eps of a point's distance to an axis-parallel
      // line is (1 + eps) times the L-inf one): the ball left of (below, right of, above) it.
      {Eps::of(-1, -1), Eps(0)}, {Eps(0), Eps::of(-1, -1)}, {Eps::of(1, 1), Eps(0)}, {Eps(0), Eps::of(1, 1)},
  };
  return s;
}
// Side 8 + segment_side(...): the side of an axis-parallel segment's line that its arc (Boost's
// site event, possibly inverted) lies on: the right of point0 -> point1.
constexpr int kLineLeftOfIt = 8, kLineBelowIt = 9, kLineRightOfIt = 10, kLineAboveIt = 11;
template <typename Site>
int segment_side(const Site& s) {
  if (s.x0() == s.x1()) return s.y1() > s.y0() ? kLineRightOfIt : kLineLeftOfIt;  // up: right is +x
  return s.x1() > s.x0() ? kLineBelowIt : kLineAboveIt;
}

inline int orientation(std::int64_t ax, std::int64_t ay, std::int64_t bx, std::int64_t by, std::int64_t cx,
                       std::int64_t cy) {
  const __int128 v = __int128(bx - ax) * (cy - ay) - __int128(by - ay) * (cx - ax);
  return v > 0 ? 1 : (v < 0 ? -1 : 0);
}

// The ball of N_eps through three points, if there is one: centre, radius and the sweep
// position at which the sweep line touches it. Each point lies on one side of the ball; for
// each choice of sides the centre solves a 3x3 linear system, and it is the ball only if the
// chosen side is the outermost for each point.
struct Ball {
  Eps cx, cy, r, den;  // centre (cx, cy) / den, radius r / den; den > 0
};

// The ball for sides side[0..2] of the three sites (anchors x, y: a point site, or a point of
// a segment's line, whose side is one of the line forms 8..11), if each point's side is the
// outermost at its centre. Rows (alpha, beta, -1) . (cx, cy, r) = alpha x + beta y, by
// Cramer's rule through the 2x2 minors of the sides (the third column is constant).
inline bool ball_on_sides(const std::int64_t x[3], const std::int64_t y[3], const int side[3], Ball& out) {
  const Side* S = sides();
  const Side &f1 = S[side[0]], &f2 = S[side[1]], &f3 = S[side[2]];
  const Eps m12 = f1.alpha * f2.beta - f2.alpha * f1.beta, m13 = f1.alpha * f3.beta - f3.alpha * f1.beta,
            m23 = f2.alpha * f3.beta - f3.alpha * f2.beta;
  Eps d = -(m23 - m13 + m12);
  if (d.sign() == 0) return false;
  const Eps h1 = f1.alpha * Eps(x[0]) + f1.beta * Eps(y[0]), h2 = f2.alpha * Eps(x[1]) + f2.beta * Eps(y[1]),
            h3 = f3.alpha * Eps(x[2]) + f3.beta * Eps(y[2]);
  Eps cx = -(h2 * f3.beta - h3 * f2.beta - h1 * f3.beta + h3 * f1.beta + h1 * f2.beta - h2 * f1.beta);
  Eps cy = -(f2.alpha * h3 - f3.alpha * h2 - f1.alpha * h3 + f3.alpha * h1 + f1.alpha * h2 - f2.alpha * h1);
  Eps r = h1 * m23 - h2 * m13 + h3 * m12;
  if (d.sign() < 0) d = -d, cx = -cx, cy = -cy, r = -r;
  if (r.sign() < 0) return false;  // radius 0: a corner, where two edges meet their common end
  for (int a = 0; a < 3; ++a) {
    if (side[a] >= 8) continue;  // a line: touched by construction
    const Eps u = cx - Eps(x[a]) * d, v = cy - Eps(y[a]) * d;
    for (int k = 0; k < 8; ++k) {
      if (k == side[a]) continue;
      // At eps = 0 a side's form is +-u or +-v: strictly below r there, it is below r.
      const std::int64_t v0 = k < 4 ? (k < 2 ? u.c[0] : -u.c[0]) : (k < 6 ? v.c[0] : -v.c[0]);
      if (v0 < r.c[0]) continue;
      if ((S[k].alpha * u + S[k].beta * v - r).sign() > 0) return false;
    }
  }
  out.cx = cx, out.cy = cy, out.r = r, out.den = d;
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

// Every vertex of the set of L-inf squares through the three sites (a point on a side of the
// square, a segment's line on the side facing it): three independent conditions, each "point
// a on side s" (up to two a point, at a corner) or a line's (each line's among them), met by a
// square that holds all the points. The bits of the sides each point lies on at some vertex
// are or-ed into cand (both eps sides of each L-inf side). In doubled coordinates: exact.
inline bool square_vertex_sides(const std::int64_t x[3], const std::int64_t y[3], const int fixed[3], unsigned cand[3]) {
  static const int A[12] = {1, -1, 0, 0, 0, 0, 0, 0, -1, 0, 1, 0}, B[12] = {0, 0, 1, -1, 0, 0, 0, 0, 0, -1, 0, 1};
  int cons[12][2], n = 0, lines = 0;  // (site, L-inf side 0..3 or line form 8..11)
  for (int a = 0; a < 3; ++a) {
    if (fixed[a] >= 0) {
      cons[n][0] = a, cons[n][1] = fixed[a], ++n, ++lines;
    } else {
      for (int sd = 0; sd < 4; ++sd) cons[n][0] = a, cons[n][1] = sd, ++n;
    }
  }
  bool any = false;
  for (int c1 = 0; c1 < n; ++c1)
    for (int c2 = c1 + 1; c2 < n; ++c2)
      for (int c3 = c2 + 1; c3 < n; ++c3) {
        const int cs[3] = {c1, c2, c3};
        int with_lines = 0;
        for (int c : cs) with_lines += cons[c][1] >= 8;
        if (with_lines != lines) continue;
        // Rows (A, B, -1) . (cx, cy, r) = A x_a + B y_a.
        std::int64_t m[3][3], h[3];
        for (int t = 0; t < 3; ++t) {
          const int a = cons[cs[t]][0], sd = cons[cs[t]][1];
          m[t][0] = A[sd], m[t][1] = B[sd], m[t][2] = -1, h[t] = A[sd] * x[a] + B[sd] * y[a];
        }
        auto det = [](const std::int64_t q[3][3]) {
          return q[0][0] * (q[1][1] * q[2][2] - q[1][2] * q[2][1]) - q[0][1] * (q[1][0] * q[2][2] - q[1][2] * q[2][0]) +
                 q[0][2] * (q[1][0] * q[2][1] - q[1][1] * q[2][0]);
        };
        const std::int64_t d = det(m);
        if (d == 0) continue;
        std::int64_t sol[3];  // doubled: 2 * numerator / d is an integer, d being +-1 or +-2
        for (int c = 0; c < 3; ++c) {
          std::int64_t q[3][3];
          for (int t = 0; t < 3; ++t)
            for (int u = 0; u < 3; ++u) q[t][u] = u == c ? h[t] : m[t][u];
          sol[c] = 2 * det(q) / d;
        }
        if (sol[2] < 0) continue;
        bool ok = true;
        for (int a = 0; a < 3 && ok; ++a)
          if (fixed[a] < 0) ok = std::max(std::llabs(sol[0] - 2 * x[a]), std::llabs(sol[1] - 2 * y[a])) == sol[2];
        if (!ok) continue;
        any = true;
        for (int a = 0; a < 3; ++a) {
          if (fixed[a] >= 0) continue;
          const std::int64_t u = sol[0] - 2 * x[a], v = sol[1] - 2 * y[a];
          if (u == sol[2]) cand[a] |= 0x03u;
          if (-u == sol[2]) cand[a] |= 0x0cu;
          if (v == sol[2]) cand[a] |= 0x30u;
          if (-v == sol[2]) cand[a] |= 0xc0u;
        }
      }
  return any;
}

// Where a ball touches a segment's line: its centre's x (a horizontal line) or y (a vertical
// one) must lie within the segment's closed span [lo, hi], or the ball touches the line
// beside the segment.
struct Span {
  std::int64_t lo = 0, hi = -1;  // empty: a point site
};
inline bool touches_within(const Ball& b, int side, const Span& sp) {
  if (sp.hi < sp.lo) return true;
  const Eps& c = (side == kLineBelowIt || side == kLineAboveIt) ? b.cx : b.cy;
  return (c - Eps(sp.lo) * b.den).sign() >= 0 && (Eps(sp.hi) * b.den - c).sign() >= 0;
}

// Whether the ball meets the three sites counter-clockwise (bottom arc, middle, top): where
// it touches a point is the point, a horizontal line (cx, y0), a vertical one (x0, cy). An
// event whose middle arc vanishes meets them clockwise (as the three points of Boost's point
// case must turn); touches that coincide (a corner, an edge at its own end) decide nothing.
inline bool turns_left(const std::int64_t x[3], const std::int64_t y[3], const int side[3], const Ball& b) {
  Eps tx[3], ty[3];  // times den
  for (int a = 0; a < 3; ++a) {
    const bool horizontal_line = side[a] == kLineBelowIt || side[a] == kLineAboveIt;
    const bool vertical_line = side[a] == kLineLeftOfIt || side[a] == kLineRightOfIt;
    tx[a] = horizontal_line ? b.cx : Eps(x[a]) * b.den;
    ty[a] = vertical_line ? b.cy : Eps(y[a]) * b.den;
  }
  return sign_of_cross(tx[1] - tx[0], ty[1] - ty[0], tx[2] - tx[0], ty[2] - ty[0]) > 0;
}

// The first choice of sides among the candidates (bit k of cand[a]: side k for site a) that
// gives a ball touching the segments within their spans.
inline bool ball_among(const std::int64_t x[3], const std::int64_t y[3], const unsigned cand[3], Ball& out,
                       const Span* spans = nullptr) {
  for (int i = 0; i < 12; ++i) {
    if (!(cand[0] >> i & 1u)) continue;
    for (int j = 0; j < 12; ++j) {
      if (!(cand[1] >> j & 1u)) continue;
      for (int k = 0; k < 12; ++k) {
        if (!(cand[2] >> k & 1u)) continue;
        const int side[3] = {i, j, k};
        if (!ball_on_sides(x, y, side, out)) continue;
        if (spans && !(touches_within(out, i, spans[0]) && touches_within(out, j, spans[1]) &&
                       touches_within(out, k, spans[2])))
          continue;
        if (spans && turns_left(x, y, side, out)) continue;
        return true;
      }
    }
  }
  return false;
}

// The ball of N_eps through three points, with a radius that stays finite as eps -> 0 (one
// that does not meets the sweep line beyond every finite event: the limit diagram has two
// parallel rays there, no vertex). Such a ball tends to an L-inf square through the points:
// a vertex of the set of such squares or a point of an edge of it, where each point lies on
// sides it lies on at the edge's ends. Those sides (either eps side of each: the minor
// coordinate can change sign along an edge) are the candidates. The squares squares_through
// gives are most often enough; else all the vertices; every choice of sides is the last resort.
inline bool ball_through(const std::int64_t x[3], const std::int64_t y[3], Ball& out) {
  unsigned cand[3] = {0, 0, 0};
  bool any = false;
  squares_through(x, y, [&](double cx, double cy, double) {
    any = true;
    for (int a = 0; a < 3; ++a) {
      const double u = cx - double(x[a]), v = cy - double(y[a]), m = std::max(std::fabs(u), std::fabs(v));
      if (u == m) cand[a] |= 0x03u;
      if (-u == m) cand[a] |= 0x0cu;
      if (v == m) cand[a] |= 0x30u;
      if (-v == m) cand[a] |= 0xc0u;
    }
  });
  if (!any) return false;
  if (ball_among(x, y, cand, out)) return true;
  const unsigned first[3] = {cand[0], cand[1], cand[2]};
  const int none[3] = {-1, -1, -1};
  square_vertex_sides(x, y, none, cand);
  if ((cand[0] != first[0] || cand[1] != first[1] || cand[2] != first[2]) && ball_among(x, y, cand, out)) return true;
  const unsigned all[3] = {0xffu, 0xffu, 0xffu};
  return ball_among(x, y, all, out);
}

// The ball touching three sites of which some are segments (fixed[a]: the side of its line
// the segment's arc faces, or -1 for a point; x, y: the point, or the segment's point0), at a
// point of each segment (spans).
inline bool ball_touching(const std::int64_t x[3], const std::int64_t y[3], const int fixed[3], const Span spans[3],
                          Ball& out) {
  unsigned cand[3] = {0, 0, 0};
  for (int a = 0; a < 3; ++a)
    if (fixed[a] >= 0) cand[a] = 1u << fixed[a];
  const unsigned lines[3] = {cand[0], cand[1], cand[2]};
  if (!square_vertex_sides(x, y, fixed, cand)) return false;
  if (ball_among(x, y, cand, out, spans)) return true;
  unsigned all[3];
  for (int a = 0; a < 3; ++a) all[a] = fixed[a] >= 0 ? lines[a] : 0xffu;
  return ball_among(x, y, all, out, spans);
}

inline int orientation128(std::int64_t ax, std::int64_t ay, std::int64_t bx, std::int64_t by) {
  const __int128 v = __int128(ax) * by - __int128(ay) * bx;
  return v > 0 ? 1 : (v < 0 ? -1 : 0);
}

}  // namespace linf::sweep
