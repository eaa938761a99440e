// The sweep's geometry: Boost.Polygon's voronoi_builder (beach line, site and circle events)
// with the predicates of the L-inf ownership rule in place of the Euclidean ones.
//
// Boost's builder takes its predicates as a template parameter (VP) and holds event positions
// in a type of ours (fpt_type, here Ratio): the algorithm is Boost's, the geometry is ours, as
// in CGAL's traits classes. Distances are those of N_eps = L-inf + eps L1 for an infinitesimal
// eps (eps.hpp), so every decision is exact and the ties of L-inf are the L1 tie-break's.
//
// A site's "arc" at sweep position L is the set of points q with N_eps(q - s) = (1 + eps)(L - q.x),
// the N_eps distance from q to the sweep line. Events happen where the sweep line touches a
// ball of N_eps: its rightmost point is the vertex (1/(1+eps), 0), so an event has the y of
// its centre.
//
// Point sites only, so far: the builder (sweep.cpp) falls back to the subdivision for segments.
#pragma once
#include <boost/polygon/detail/voronoi_structures.hpp>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <stdexcept>

#include "diagram/sweep/eps.hpp"

namespace linf::sweep {

struct CoordinateTraits {
  typedef std::int32_t int_type;
  typedef Ratio fpt_type;
};

namespace bpd = boost::polygon::detail;

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

// How far left of `p` (on its horizontal) the arc of point site s lies when the sweep is at
// p.x: the root t of N_eps(p.x - t - s.x, p.y - s.y) = (1 + eps) t. N_eps is the largest of
// its sides' forms and each form's equation falls in t, so the root is the largest of their
// roots; the sides facing left (alpha = -(1 + eps)) have none unless p.x = s.x.
// Returns false where the arc does not reach p's height (p.x = s.x, p.y != s.y).
inline bool arc_distance(std::int64_t sx, std::int64_t sy, std::int64_t px, std::int64_t py, Ratio& t) {
  const std::int64_t dx = px - sx, dy = py - sy;
  if (dx == 0) {
    t = Ratio(0);
    return dy == 0;
  }
  const Eps one_eps = Eps::of(1, 1);
  bool any = false;
  for (int k = 0; k < 8; ++k) {
    const Side& f = sides()[k];
    if (k == 2 || k == 3) continue;
    const Ratio r(f.alpha * Eps(dx) + f.beta * Eps(dy), one_eps + f.alpha);
    if (!any || compare(r, t) > 0) t = r, any = true;
  }
  return true;
}

// Whether the arc of point site b lies nearer p (on p's horizontal) than that of a: the
// sign of t_a - t_b. At eps = 0, t = max(dx / 2, |dy|); only its ties need the eps terms.
inline int arc_nearer(std::int64_t ax, std::int64_t ay, std::int64_t bx, std::int64_t by, std::int64_t px,
                      std::int64_t py) {
  const bool reach_a = px != ax || py == ay, reach_b = px != bx || py == by;
  if (!reach_a || !reach_b) return reach_a == reach_b ? 0 : (reach_b ? 1 : -1);
  const std::int64_t ta = std::max<std::int64_t>(px - ax, 2 * std::llabs(py - ay));
  const std::int64_t tb = std::max<std::int64_t>(px - bx, 2 * std::llabs(py - by));
  if (ta != tb) return ta > tb ? 1 : -1;
  Ratio ra, rb;
  arc_distance(ax, ay, px, py, ra);
  arc_distance(bx, by, px, py, rb);
  return compare(ra, rb);
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

struct Predicates {
  template <typename Point>
  static bool is_vertical(const Point& p1, const Point& p2) {
    return p1.x() == p2.x();
  }
  template <typename Site>
  static bool is_vertical(const Site& s) {
    return is_vertical(s.point0(), s.point1());
  }

  template <typename Point>
  struct point_comparison_predicate {
    bool operator()(const Point& l, const Point& r) const { return l.x() == r.x() ? l.y() < r.y() : l.x() < r.x(); }
  };

  template <typename Site, typename Circle>
  struct event_comparison_predicate {
    // Sites among themselves: as Boost's (no geometry but the order of segments at a point).
    bool operator()(const Site& l, const Site& r) const {
      if (l.x0() != r.x0()) return l.x0() < r.x0();
      if (!l.is_segment()) {
        if (!r.is_segment()) return l.y0() < r.y0();
        if (is_vertical(r)) return l.y0() <= r.y0();
        return true;
      }
      if (is_vertical(r)) return is_vertical(l) ? l.y0() < r.y0() : false;
      if (is_vertical(l)) return true;
      if (l.y0() != r.y0()) return l.y0() < r.y0();
      return orientation(l.x1(), l.y1(), l.x0(), l.y0(), r.x1(), r.y1()) > 0;
    }
    bool operator()(const Site& l, const Circle& r) const { return compare(Ratio(l.x0()), r.lower_x()) < 0; }
    bool operator()(const Circle& l, const Site& r) const { return compare(l.lower_x(), Ratio(r.x0())) < 0; }
    bool operator()(const Circle& l, const Circle& r) const {
      const int c = compare(l.lower_x(), r.lower_x());
      return c != 0 ? c < 0 : compare(l.y(), r.y()) < 0;
    }
  };

  // Whether the horizontal through a new point meets the right (upper) arc of the pair first,
  // i.e. the point lies above their breakpoint; false on the breakpoint. Boost's structure:
  // the shortcuts tell which of two crossings a node stands for, the arcs' distances decide
  // the rest. A segment's arc is at the distance of its line, which for an axis-parallel line
  // is the same in N_eps as in L2 (|dy|, or dx / 2 for a vertical one), so the segment cases'
  // shortcuts (sides of lines, the 45-degree lines through a point) hold as they are.
  template <typename Site>
  struct distance_predicate {
    template <typename Point>
    bool operator()(const Site& left, const Site& right, const Point& p) const {
      if (!left.is_segment()) {
        if (!right.is_segment()) return pp(left, right, p);
        return ps(left, right, p, false);
      }
      if (!right.is_segment()) return ps(right, left, p, true);
      return ss(left, right, p);
    }

   private:
    template <typename Point>
    static bool pp(const Site& left, const Site& right, const Point& p) {
      const auto &a = left.point0(), &b = right.point0();
      if (a.x() > b.x()) {
        if (p.y() <= a.y()) return false;  // the newer arc below: the breakpoint is above it
      } else if (a.x() < b.x()) {
        if (p.y() >= b.y()) return true;
      } else {
        return std::int64_t(a.y()) + b.y() < 2 * std::int64_t(p.y());
      }
      return arc_nearer(a.x(), a.y(), b.x(), b.y(), p.x(), p.y()) > 0;
    }

    // t of a segment's arc (its line's) at p's height, the sweep at p.x; negative where p is on
    // the other side of the line than the arc (as Boost's signed distance): that arc is never
    // met there.
    template <typename Point>
    static Ratio segment_arc(const Site& s, const Point& p) {
      if (s.x0() == s.x1()) return Ratio(Eps(std::int64_t(p.x()) - s.x0()), Eps(2));
      const std::int64_t dy = std::int64_t(p.y()) - s.y0();
      return Ratio(s.x1() > s.x0() ? -dy : dy);  // the arc is on the right of point0 -> point1
    }

    enum { kLess = -1, kUndefined = 0, kMore = 1 };

    template <typename Point>
    static int fast_ps(const Site& point, const Site& seg, const Point& p, bool reverse) {
      const auto& a = point.point0();
      const std::int64_t sx0 = seg.x0(), sy0 = seg.y0(), sx1 = seg.x1(), sy1 = seg.y1();
      if (orientation(sx0, sy0, sx1, sy1, p.x(), p.y()) != -1) return !seg.is_inverse() ? kLess : kMore;
      const std::int64_t dx = std::int64_t(p.x()) - a.x(), dy = std::int64_t(p.y()) - a.y();
      if (sx0 == sx1) {
        if (p.y() < a.y() && !reverse) return kMore;
        if (p.y() > a.y() && reverse) return kLess;
        return kUndefined;
      }
      if (orientation128(sx1 - sx0, sy1 - sy0, dx, dy) == 1) {
        if (!seg.is_inverse()) return reverse ? kLess : kUndefined;
        return reverse ? kUndefined : kMore;
      }
      // Boost's a (dy + dx)(dy - dx) against 2 b dx dy, b = 0 for a horizontal segment: which
      // side of the 45-degree lines through the point.
      const __int128 l = __int128(sx1 - sx0) * (dy + dx) * (dy - dx), r = __int128(2) * (sy1 - sy0) * dx * dy;
      if (l != r) {
        if ((l > r) ^ reverse) return reverse ? kLess : kMore;
        return kUndefined;
      }
      return kUndefined;
    }

    template <typename Point>
    static bool ps(const Site& point, const Site& seg, const Point& p, bool reverse) {
      const int fast = fast_ps(point, seg, p, reverse);
      if (fast != kUndefined) return fast == kLess;
      Ratio tp;
      const bool reach = arc_distance(point.x0(), point.y0(), p.x(), p.y(), tp);
      const Ratio ts = segment_arc(seg, p);
      // Boost: reverse ^ (dist_point < dist_segment), its distances being -t.
      const bool point_farther = !reach || compare(tp, ts) > 0;
      return reverse ^ point_farther;
    }

    template <typename Point>
    static bool ss(const Site& left, const Site& right, const Point& p) {
      if (left.sorted_index() == right.sorted_index())  // a segment's two arcs: its own line
        return orientation(left.x0(), left.y0(), left.x1(), left.y1(), p.x(), p.y()) == 1;
      return compare(segment_arc(left, p), segment_arc(right, p)) > 0;
    }
  };

  // Boost's node comparison, unchanged: which of two beach-line nodes comes first, one of them
  // the new site's; the geometry is the distance predicate's.
  template <typename Node>
  class node_comparison_predicate {
   public:
    typedef typename Node::site_type site_type;
    typedef typename site_type::point_type point_type;
    typedef typename point_type::coordinate_type coordinate_type;

    bool operator()(const Node& node1, const Node& node2) const {
      const site_type& site1 = get_comparison_site(node1);
      const site_type& site2 = get_comparison_site(node2);
      const point_type& point1 = get_comparison_point(site1);
      const point_type& point2 = get_comparison_point(site2);
      if (point1.x() < point2.x()) return distance_(node1.left_site(), node1.right_site(), point2);
      if (point1.x() > point2.x()) return !distance_(node2.left_site(), node2.right_site(), point1);
      if (site1.sorted_index() == site2.sorted_index()) return get_comparison_y(node1) < get_comparison_y(node2);
      if (site1.sorted_index() < site2.sorted_index()) {
        std::pair<coordinate_type, int> y1 = get_comparison_y(node1, false);
        std::pair<coordinate_type, int> y2 = get_comparison_y(node2, true);
        if (y1.first != y2.first) return y1.first < y2.first;
        return (!site1.is_segment()) ? (y1.second < 0) : false;
      }
      std::pair<coordinate_type, int> y1 = get_comparison_y(node1, true);
      std::pair<coordinate_type, int> y2 = get_comparison_y(node2, false);
      if (y1.first != y2.first) return y1.first < y2.first;
      return (!site2.is_segment()) ? (y2.second > 0) : true;
    }

   private:
    const site_type& get_comparison_site(const Node& node) const {
      return node.left_site().sorted_index() > node.right_site().sorted_index() ? node.left_site()
                                                                                : node.right_site();
    }
    const point_type& get_comparison_point(const site_type& site) const {
      return point_comparison_predicate<point_type>()(site.point0(), site.point1()) ? site.point0() : site.point1();
    }
    std::pair<coordinate_type, int> get_comparison_y(const Node& node, bool is_new_node = true) const {
      if (node.left_site().sorted_index() == node.right_site().sorted_index())
        return std::make_pair(node.left_site().y0(), 0);
      if (node.left_site().sorted_index() > node.right_site().sorted_index()) {
        if (!is_new_node && node.left_site().is_segment() && is_vertical(node.left_site()))
          return std::make_pair(node.left_site().y0(), 1);
        return std::make_pair(node.left_site().y1(), 1);
      }
      return std::make_pair(node.right_site().y0(), -1);
    }
    distance_predicate<site_type> distance_;
  };

  // Three consecutive arcs (bottom to top) whose middle one will vanish: Boost's existence
  // tests (orientations of the sites and of the segments' arcs, no metric in them) and a ball
  // of N_eps touching the three: the points on it, each segment's line from its arc's side.
  template <typename Site, typename Circle>
  struct circle_formation_predicate {
    bool operator()(const Site& s1, const Site& s2, const Site& s3, Circle& c) const {
      const Site* s[3] = {&s1, &s2, &s3};
      int segments = 0;
      for (const Site* t : s) segments += t->is_segment();
      if (segments == 0) {
        if (orientation(s1.x(), s1.y(), s2.x(), s2.y(), s3.x(), s3.y()) >= 0) return false;
      } else if (!s1.is_segment() && !s2.is_segment()) {
        if (!pps(s1, s2, s3, 3)) return false;
      } else if (!s1.is_segment() && !s3.is_segment()) {
        if (!pps(s1, s3, s2, 2)) return false;
      } else if (!s2.is_segment() && !s3.is_segment()) {
        if (!pps(s2, s3, s1, 1)) return false;
      } else if (!s1.is_segment()) {
        if (!pss(s1, s2, s3, 1)) return false;
      } else if (!s2.is_segment()) {
        if (!pss(s2, s1, s3, 2)) return false;
      } else if (!s3.is_segment()) {
        if (!pss(s3, s1, s2, 3)) return false;
      } else if (s1.sorted_index() == s2.sorted_index() || s2.sorted_index() == s3.sorted_index()) {
        return false;
      }
      std::int64_t x[3], y[3];
      int fixed[3];
      Span spans[3];
      for (int a = 0; a < 3; ++a) {
        const Site& t = *s[a];
        x[a] = t.x0(), y[a] = t.y0();
        fixed[a] = t.is_segment() ? segment_side(t) : -1;
        if (t.is_segment())
          spans[a] = t.y0() == t.y1() ? Span{std::min<std::int64_t>(t.x0(), t.x1()), std::max<std::int64_t>(t.x0(), t.x1())}
                                      : Span{std::min<std::int64_t>(t.y0(), t.y1()), std::max<std::int64_t>(t.y0(), t.y1())};
      }
      Ball b;
      if (segments == 0 ? !ball_through(x, y, b) : !ball_touching(x, y, fixed, spans, b)) return false;
      const Eps one_eps = Eps::of(1, 1);
      c = Circle(Ratio(b.cx, b.den), Ratio(b.cy, b.den), Ratio(b.cx * one_eps + b.r, b.den * one_eps));
      // Boost's last test: a vertical segment's arc ends at its endpoints' heights.
      for (const Site* t : s) {
        if (!t->is_segment() || t->x0() != t->x1()) continue;
        const std::int64_t lo = std::min(t->y0(), t->y1()), hi = std::max(t->y0(), t->y1());
        if (compare(c.y(), Ratio(lo)) < 0 || compare(c.y(), Ratio(hi)) > 0) return false;
      }
      return true;
    }

   private:
    // Boost's circle_existence_predicate for two points and a segment (segment_index: where
    // the segment is among the three arcs) and for a point and two segments (point_index).
    static bool pps(const Site& p1, const Site& p2, const Site& seg, int segment_index) {
      if (segment_index != 2) {
        const int o1 = orientation(p1.x(), p1.y(), p2.x(), p2.y(), seg.x0(), seg.y0());
        const int o2 = orientation(p1.x(), p1.y(), p2.x(), p2.y(), seg.x1(), seg.y1());
        if (segment_index == 1 && p1.x0() >= p2.x0()) {
          if (o1 != -1) return false;
        } else if (segment_index == 3 && p2.x0() >= p1.x0()) {
          if (o2 != -1) return false;
        } else if (o1 != -1 && o2 != -1) {
          return false;
        }
        return true;
      }
      return seg.point0() != p1.point0() || seg.point1() != p2.point0();
    }
    static bool pss(const Site& p, const Site& s2, const Site& s3, int point_index) {
      if (s2.sorted_index() == s3.sorted_index()) return false;
      if (point_index == 2) {
        if (!s2.is_inverse() && s3.is_inverse()) return false;
        if (s2.is_inverse() == s3.is_inverse() &&
            orientation(s2.x0(), s2.y0(), p.x0(), p.y0(), s3.x1(), s3.y1()) != -1)
          return false;
      }
      return true;
    }
  };
};

}  // namespace linf::sweep
