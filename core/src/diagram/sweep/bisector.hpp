// The bisector of two sites under the ownership rule, for points and axis-parallel segments,
// as a function along one axis: the parameter p (x or y) and the other coordinate f(p), with a
// straight middle part over [mid_p - half, mid_p + half] and straight parts beyond it.
//
// * Two points with |dx| >= |dy|: x(y), the perpendicular of the major axis through the
//   midpoint for y within (|dx| - |dy|) / 2 of it, 45-degree rays beyond, turning the same way;
//   dy = 0: the whole perpendicular (the L-inf ties of the wedges above and below go by L1).
// * A point and a horizontal segment's line, the point off it: y(x), flat half way between
//   them for x within half their distance of the point, then 45 degrees down towards the
//   point's side (a roof over a point below the line). On the line (the segment's own end, or
//   a point in line with it): the perpendicular through the point, by L1.
// * Two parallel segments: the middle line. A horizontal and a vertical segment: one of the
//   diagonals through their lines' crossing; the sweep gives both its ends (the segments'
//   strips cross in a bounded box), and the piece is the straight segment between them.
// Vertical cases are the horizontal ones with the axes swapped.
// With a slanted segment the bisector is a polyline (Chain, below).
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <utility>

#include "diagram/sweep/eps.hpp"
#include "linf/geometry/site.hpp"

namespace linf::sweep {

// The line a x + b y = c, its coefficients exact integers (a slanted site's normal makes them
// up to 2^94): where a piece of it is cut at a tile's side, the other coordinate follows from
// the side alone, so the same cut from any tile has the same bits.
struct Line {
  __int128 a = 0, b = 0, c = 0;
  double y_at(double x) const { return solve(c, a, b, x); }
  double x_at(double y) const { return solve(c, b, a, y); }

 private:
  // (c - a t) / b: exact up to the last division where 2t is an integer (a tile's side is),
  // else in long double.
  static double solve(__int128 c, __int128 a, __int128 b, double t) {
    const double t2 = 2 * t;
    if (t2 == std::floor(t2) && std::fabs(t2) < 0x1p62) {
      const __int128 num = 2 * c - a * __int128(t2);
      return double(num) / double(2 * b);
    }
    return double((static_cast<long double>(c) - static_cast<long double>(a) * t) / static_cast<long double>(b));
  }
};

struct Bisector {
  bool along_y = false;  // the parameter is y (x = f(y)); else x (y = f(x))
  bool straight = false; // a diagonal between two segments: the piece joins its two vertices
  double mid_p = 0, mid_f = 0, half = 0;
  double slope_lo = 0, slope_hi = 0;  // df/dp below mid_p - half and above mid_p + half

  Bisector(const Site& s, const Site& t) {
    const bool ps = s.is_point(), pt = t.is_point();
    if (ps && pt) {
      points(s.a, t.a);
      return;
    }
    if (ps != pt) {
      point_line(ps ? s.a : t.a, ps ? t : s);
      return;
    }
    const bool hs = s.a.y == s.b.y, ht = t.a.y == t.b.y;
    if (hs != ht) {
      straight = true;
      return;
    }
    // Parallel: the middle line. In line, they meet only where they share an end whose
    // point has a region of no width beside them (zero_width.hpp): along the
    // perpendicular there.
    along_y = !hs;
    mid_f = hs ? 0.5 * double(s.a.y + t.a.y) : 0.5 * double(s.a.x + t.a.x);
    if (hs ? s.a.y == t.a.y : s.a.x == t.a.x) {
      const Point& end = (s.a == t.a || s.a == t.b) ? s.a : s.b;
      along_y = hs;
      mid_f = hs ? double(end.x) : double(end.y);
    }
  }

  void points(const Point& s, const Point& t) {
    const std::int64_t dx = t.x - s.x, dy = t.y - s.y;
    along_y = std::llabs(dx) >= std::llabs(dy);
    const std::int64_t major = along_y ? dx : dy, minor = along_y ? dy : dx;
    mid_p = along_y ? 0.5 * double(s.y + t.y) : 0.5 * double(s.x + t.x);
    mid_f = along_y ? 0.5 * double(s.x + t.x) : 0.5 * double(s.y + t.y);
    half = 0.5 * double(std::llabs(major) - std::llabs(minor));
    const double slope = minor == 0 ? 0.0 : ((major > 0) == (minor > 0) ? -1.0 : 1.0);
    slope_lo = slope_hi = slope;
  }

  void point_line(const Point& a, const Site& seg) {
    const bool horizontal = seg.a.y == seg.b.y;
    const std::int64_t line = horizontal ? seg.a.y : seg.a.x;
    const std::int64_t along = horizontal ? a.x : a.y, across = horizontal ? a.y : a.x;
    const std::int64_t delta = line - across;
    if (delta == 0) {  // the perpendicular through the point
      along_y = horizontal;
      mid_f = double(along);
      return;
    }
    along_y = !horizontal;
    mid_p = double(along);
    mid_f = 0.5 * double(line + across);
    half = 0.5 * double(std::llabs(delta));
    const double sgn = delta > 0 ? 1.0 : -1.0;  // the line beyond the point: the roof bends back
    slope_lo = sgn, slope_hi = -sgn;
  }

  double at(double p) const {
    if (p > mid_p + half) return mid_f + slope_hi * (p - mid_p - half);
    if (p < mid_p - half) return mid_f + slope_lo * (p - mid_p + half);
    return mid_f;
  }
  double param(const Vec2& v) const { return along_y ? v.y : v.x; }
  Vec2 point(double p) const { return along_y ? Vec2{at(p), p} : Vec2{p, at(p)}; }
  bool bends() const { return half > 0 && !(slope_lo == 0 && slope_hi == 0); }

  // The line of the part holding the parameters lo..hi (between two bends or beyond one):
  // doubled, its coefficients are integers (the bends lie at halves of integers).
  Line line_between(double lo, double hi) const {
    const double m = 0.5 * (lo + hi);  // no flat part where half = 0 (two points on a diagonal)
    const double slope = m > mid_p + half ? slope_hi : m < mid_p - half || half == 0 ? slope_lo : 0.0;
    const double p0 = m > mid_p + half ? mid_p + half : mid_p - half;
    // f - slope p = mid_f - slope p0, times 2; f is x where the parameter is y.
    const __int128 k = __int128(slope), c = __int128(2 * mid_f) - k * __int128(2 * p0);
    return along_y ? Line{2, -2 * k, c} : Line{-2 * k, 2, c};
  }
  // The diagonal of two perpendicular segments through their lines' crossing that runs from p
  // to q.
  static Line diagonal(const Site& s, const Site& t, const Vec2& p, const Vec2& q) {
    const Site& h = s.a.y == s.b.y ? s : t;
    const Site& v = s.a.y == s.b.y ? t : s;
    const bool rising = (q.x - p.x) * (q.y - p.y) > 0;  // x - y = c, else x + y = c
    return rising ? Line{1, -1, __int128(v.a.x) - h.a.y} : Line{1, 1, __int128(v.a.x) + h.a.y};
  }
  // Whether site s lies on the left of the bisector with `other` walked towards growing
  // parameter: walking up x = f(y), left is smaller x; walking right along y = f(x), left is
  // larger y. A site is tested at its middle; a segment's end on the perpendicular through it
  // lies on the bisector, and is on the side its segment is not.
  bool left_of_growing(const Site& s, const Site& other) const {
    const double rx = 0.5 * double(s.a.x + s.b.x), ry = 0.5 * double(s.a.y + s.b.y);
    const double f = at(along_y ? ry : rx), g = along_y ? rx : ry;
    if (g == f) return !left_of_growing(other, s);
    return along_y ? g < f : g > f;
  }
};

// Whether s is a segment neither horizontal nor vertical (45 degrees or any other slope).
inline bool is_diagonal(const Site& s) { return !s.is_point() && s.a.x != s.b.x && s.a.y != s.b.y; }

// The bisector of two sites of which one is a slanted segment, as a polyline: v[0..n) with a
// ray into v[0] along -in (from infinity) and one out of v[n - 1] along `out`, or no rays and
// the piece between the edge's two vertices (`straight`). No L-inf tie covers an area here: a
// slanted line m . q = c has L-inf distance |m . q - c| / (|m_x| + |m_y|), gradient m / |m|_1
// with both entries nonzero, a point's and an axis-parallel line's (+-1, 0) or (0, +-1), so
// the sites' distance functions agree on lines only.
// * A point P and the line m . q = c, P on the side m . q < c at D = c - m . P (m oriented so):
//   with A = |m_x|, B = |m_y|, u = s_x (x - P.x), v = s_y (y - P.y) (s = sgn m) the line's
//   distance is (D - A u - B v) / (A + B), P's max(|u|, |v|); equal on
//   (-D/2B, D/2B), (D/2(A+B), D/2(A+B)), (D/2A, -D/2A), the inner parts A u + (A + 2B) v = D
//   and (2A + B) u + B v = D, both rays along (-1, -1): a U around P (along that direction both
//   distances grow alike). At 45 degrees: (-D/2, D/2), (D/4, D/4), (D/2, -D/2). P on the line
//   (a segment's own end): the line P + t sgn(m) (the L-inf nearest point of a slanted line is
//   unique, reached along sgn(m): N_eps's diagonal vertex).
// * Two parallel slanted lines: the middle line. Two lines that cross (a slanted one and any
//   other): a line through the crossing, bounded by the segments' strips; the sweep gives both
//   its ends.
struct Chain {
  Vec2 v[3];
  Line parts[2];  // the lines of v[0]-v[1] and v[1]-v[2]
  Line rays[2];   // the in-ray's and the out-ray's (diagonal, but from bends rounded from rationals)
  Line whole;     // n = 1: the middle line of two parallel slanted lines, or the diagonal through
                  // a slanted segment's own end (from that integer end, not from the vertices)
  bool has_whole = false;
  int n = 0;
  Vec2 in{0, 0}, out{0, 0};  // steps of the rays, the larger entry +-1
  bool straight = false;
  // Whether the chain, walked from its in-ray to its out-ray, has `point` (the point site, or
  // one of two parallel segments) on its left; the other site is on the other side. A point on
  // the chain (a segment's own end) counts as lying opposite its segment.
  bool left_is_point = false;
  const Site* point = nullptr;

  Chain(const Site& s, const Site& t) {
    if (s.is_point() || t.is_point()) {
      point_line(s.is_point() ? s : t, s.is_point() ? t : s);
      return;
    }
    if (!is_diagonal(s) || !is_diagonal(t) || line_m(s) != line_m(t)) {
      straight = true;  // lines that cross
      return;
    }
    // Parallel: m . q = c, c half way between the lines, walked along (m_y, -m_x), which has m
    // on its left.
    const auto m = line_m(s);
    const __int128 cs = form(m, s.a), ct = form(m, t.a);
    if (cs == ct) {  // in line: as Bisector's, along sgn(m) through the shared end
      const Point& end = (s.a == t.a || s.a == t.b) ? s.a : s.b;
      const Point& mid_s = s.a == end ? s.b : s.a;  // s lies along its line from the shared end
      const std::array<std::int64_t, 2> d = sgn(m);
      n = 1;
      v[0] = {double(end.x), double(end.y)};
      in = out = {double(d[0]), double(d[1])};
      whole = through(end, d), has_whole = true;
      point = &s;
      left_is_point = double(mid_s.x - end.x) * double(-d[1]) + double(mid_s.y - end.y) * double(d[0]) > 0;
      return;
    }
    n = 1;
    v[0] = {0.5 * (double(s.a.x) + double(t.a.x)), 0.5 * (double(s.a.y) + double(t.a.y))};  // on the middle line
    const double big = double(std::max(std::llabs(m[0]), std::llabs(m[1])));
    in = out = {double(m[1]) / big, double(-m[0]) / big};
    whole = {2 * __int128(m[0]), 2 * __int128(m[1]), cs + ct}, has_whole = true;
    point = &s;  // stands for s here: s on the left where its line lies beyond the middle
    left_is_point = cs > ct;
  }

  // m of a slanted segment's line: its normal (-dy, dx) / gcd with m_x > 0.
  static std::array<std::int64_t, 2> line_m(const Site& d) {
    std::int64_t dx = std::int64_t(d.b.x) - d.a.x, dy = std::int64_t(d.b.y) - d.a.y;
    std::int64_t g = std::llabs(dx), h = std::llabs(dy);
    while (h) g %= h, std::swap(g, h);
    dx /= g, dy /= g;
    return dy < 0 ? std::array<std::int64_t, 2>{-dy, dx} : std::array<std::int64_t, 2>{dy, -dx};
  }
  static std::array<std::int64_t, 2> sgn(const std::array<std::int64_t, 2>& m) {
    return {m[0] > 0 ? 1 : -1, m[1] > 0 ? 1 : -1};
  }
  // The diagonal through the integer point e along d (entries +-1): d_y x - d_x y = d_y e_x - d_x e_y.
  // A piece of it cut at a tile's side from a vertex rounded from a rational (the piece's other
  // end) would carry that vertex's rounding; from this line the cut has the same bits in every tile.
  static Line through(const Point& e, const std::array<std::int64_t, 2>& d) {
    return {d[1], -d[0], __int128(d[1]) * e.x - __int128(d[0]) * e.y};
  }
  static __int128 form(const std::array<std::int64_t, 2>& m, const Point& p) {
    return __int128(m[0]) * p.x + __int128(m[1]) * p.y;
  }

  void point_line(const Site& p, const Site& seg) {
    auto m = line_m(seg);
    __int128 D = form(m, seg.a) - form(m, p.a);
    point = &p;
    if (D == 0) {  // P + t sgn(m), walked along it: the segment's other end lies on one side
      const std::array<std::int64_t, 2> d = sgn(m);
      n = 1;
      v[0] = {double(p.a.x), double(p.a.y)};
      in = out = {double(d[0]), double(d[1])};
      whole = through(p.a, d), has_whole = true;
      const Point other = seg.a == p.a ? seg.b : seg.a;
      // The segment on the left of d where (other - P) . (-d_y, d_x) > 0; P counts as the
      // other side.
      left_is_point = double(other.x - p.a.x) * double(-d[1]) + double(other.y - p.a.y) * double(d[0]) < 0;
      return;
    }
    if (D < 0) m = {-m[0], -m[1]}, D = -D;
    const std::int64_t A = std::llabs(m[0]), B = std::llabs(m[1]);
    const std::int64_t sx = m[0] > 0 ? 1 : -1, sy = m[1] > 0 ? 1 : -1;
    const double mx = double(sx), my = double(sy);
    // P + (s_x u, s_y w) for u, w = k D / q, rounded once (as the sweep's vertices are: a vertex
    // at a bend has the bend's bits).
    auto at = [&](int ku, int kw, std::int64_t q) {
      return Vec2{sweep::rounded_quotient(__int128(q) * p.a.x + sx * ku * D, __int128(q)),
                  sweep::rounded_quotient(__int128(q) * p.a.y + sy * kw * D, __int128(q))};
    };
    n = 3;
    v[0] = at(-1, 1, 2 * B), v[1] = at(1, 1, 2 * (A + B)), v[2] = at(1, -1, 2 * A);
    // A u + (A + 2B) v = D and (2A + B) u + B v = D.
    const __int128 a0 = __int128(A) * sx, b0 = __int128(A + 2 * B) * sy, a1 = __int128(2 * A + B) * sx,
                   b1 = __int128(B) * sy;
    parts[0] = {a0, b0, D + a0 * p.a.x + b0 * p.a.y};
    parts[1] = {a1, b1, D + a1 * p.a.x + b1 * p.a.y};
    // Both rays run along (s_x, s_y): s_y x - s_x y is constant on each, times 2B through v[0]
    // (P + (-s_x, s_y) D / 2B) and times 2A through v[2] (P + (s_x, -s_y) D / 2A).
    const __int128 form = __int128(sy) * p.a.x - __int128(sx) * p.a.y;
    rays[0] = {2 * __int128(B) * sy, -2 * __int128(B) * sx, 2 * __int128(B) * form - 2 * __int128(sx) * sy * D};
    rays[1] = {2 * __int128(A) * sy, -2 * __int128(A) * sx, 2 * __int128(A) * form + 2 * __int128(sx) * sy * D};
    in = {mx, my};        // into v[0] along +(1, 1) in (u, v)
    out = {-mx, -my};     // out of v[2] along (-1, -1)
    // In (u, v) the walk goes clockwise round P (P on its right); a reflection with
    // s_x s_y = -1 turns it.
    left_is_point = sx * sy < 0;
  }

  // The line of part k (-1 the in-ray, 0 .. n - 2 the inner parts, n - 1 the out-ray; a single
  // line's own).
  const Line* line_of(int k) const {
    if (n == 1) return has_whole ? &whole : nullptr;
    if (k < 0) return &rays[0];
    return k + 1 < n ? &parts[k] : &rays[1];
  }

  // The bisector of two segments' lines that cross, one of them slanted: with each line's
  // L-inf distance |a x + b y - c| / w (w = |a| + |b|), the line
  // w_t (a_s x + b_s y - c_s) = +-w_s (a_t x + b_t y - c_t) through the edge's two vertices.
  static Line between_lines(const Site& s, const Site& t, const Vec2& p, const Vec2& q) {
    auto form_of = [](const Site& g, __int128& a, __int128& b, __int128& w) {
      if (g.a.y == g.b.y) a = 0, b = 1;
      else if (g.a.x == g.b.x) a = 1, b = 0;
      else {
        const auto m = line_m(g);
        a = m[0], b = m[1];
      }
      w = (a < 0 ? -a : a) + (b < 0 ? -b : b);
      return a * g.a.x + b * g.a.y;
    };
    __int128 as, bs, ws, at, bt, wt;
    const __int128 cs = form_of(s, as, bs, ws), ct = form_of(t, at, bt, wt);
    Line best;
    long double off = INFINITY;
    for (int sg : {1, -1}) {
      const Line l{wt * as - sg * ws * at, wt * bs - sg * ws * bt, wt * cs - sg * ws * ct};
      auto res = [&](const Vec2& v) {
        return std::fabs(static_cast<long double>(l.a) * v.x + static_cast<long double>(l.b) * v.y -
                         static_cast<long double>(l.c)) /
               (std::fabs(static_cast<long double>(l.a)) + std::fabs(static_cast<long double>(l.b)));
      };
      const long double e = res(p) + res(q);
      if (e < off) off = e, best = l;
    }
    return best;
  }

  // Whether site s lies on the left of the chain walked from in to out.
  bool left_of(const Site& s) const { return &s == point ? left_is_point : !left_is_point; }

  // Where q lies along the chain: (part, t), part -1 the in-ray (t <= 0, distance before
  // v[0]), 0 .. n - 2 the inner parts, n - 1 the out-ray; ordered as the walk.
  std::pair<int, double> locate(const Vec2& q) const {
    int best = -1;
    double best_d = INFINITY, best_t = 0;
    auto consider = [&](int part, const Vec2& a, const Vec2& dir, double lo, double hi) {
      const double len2 = dir.x * dir.x + dir.y * dir.y;
      double t = ((q.x - a.x) * dir.x + (q.y - a.y) * dir.y) / len2;
      t = std::clamp(t, lo, hi);
      const double ex = a.x + t * dir.x - q.x, ey = a.y + t * dir.y - q.y, d = ex * ex + ey * ey;
      if (d < best_d) best_d = d, best = part, best_t = t;
    };
    consider(-1, v[0], in, -INFINITY, 0);
    for (int i = 0; i + 1 < n; ++i) consider(i, v[i], {v[i + 1].x - v[i].x, v[i + 1].y - v[i].y}, 0, 1);
    consider(n - 1, v[n - 1], out, 0, INFINITY);
    return {best, best_t};
  }
};

}  // namespace linf::sweep
