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
  static const Side s[8] = {
      {Eps::of(1, 1), Eps::of(0, 1)},  {Eps::of(1, 1), Eps::of(0, -1)},   // x dominant, right
      {Eps::of(-1, -1), Eps::of(0, 1)}, {Eps::of(-1, -1), Eps::of(0, -1)},  // x dominant, left
      {Eps::of(0, 1), Eps::of(1, 1)},  {Eps::of(0, -1), Eps::of(1, 1)},    // y dominant, up
      {Eps::of(0, 1), Eps::of(-1, -1)}, {Eps::of(0, -1), Eps::of(-1, -1)},  // y dominant, down
  };
  return s;
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

// The ball for sides side[0..2] of the three points, if those sides are the outermost at its
// centre. Rows (alpha, beta, -1) . (cx, cy, r) = alpha x + beta y, by Cramer's rule through the
// 2x2 minors of the sides (the third column is constant).
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
  if (r.sign() <= 0) return false;
  for (int a = 0; a < 3; ++a) {
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

// Every vertex of the set of L-inf squares through the three points: three independent
// conditions "point a on side s" (up to two a point, at a corner) met by a square that holds
// all three. The bits of the sides each point lies on at some vertex are or-ed into cand
// (both eps sides of each L-inf side). In doubled coordinates, integers: exact.
inline bool square_vertex_sides(const std::int64_t x[3], const std::int64_t y[3], unsigned cand[3]) {
  static const int A[4] = {1, -1, 0, 0}, B[4] = {0, 0, 1, -1};
  bool any = false;
  for (int c1 = 0; c1 < 12; ++c1)
    for (int c2 = c1 + 1; c2 < 12; ++c2)
      for (int c3 = c2 + 1; c3 < 12; ++c3) {
        const int cs[3] = {c1, c2, c3};
        // Rows (A, B, -1) . (cx, cy, r) = A x_a + B y_a.
        std::int64_t m[3][3], h[3];
        for (int t = 0; t < 3; ++t) {
          const int a = cs[t] / 4, sd = cs[t] % 4;
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
        if (sol[2] <= 0) continue;
        bool ok = true;
        for (int a = 0; a < 3 && ok; ++a)
          ok = std::max(std::llabs(sol[0] - 2 * x[a]), std::llabs(sol[1] - 2 * y[a])) == sol[2];
        if (!ok) continue;
        any = true;
        for (int a = 0; a < 3; ++a) {
          const std::int64_t u = sol[0] - 2 * x[a], v = sol[1] - 2 * y[a];
          if (u == sol[2]) cand[a] |= 0x03u;
          if (-u == sol[2]) cand[a] |= 0x0cu;
          if (v == sol[2]) cand[a] |= 0x30u;
          if (-v == sol[2]) cand[a] |= 0xc0u;
        }
      }
  return any;
}

// The first choice of sides among the candidates (bit k of cand[a]: side k for point a) that
// gives a ball.
inline bool ball_among(const std::int64_t x[3], const std::int64_t y[3], const unsigned cand[3], Ball& out) {
  for (int i = 0; i < 8; ++i) {
    if (!(cand[0] >> i & 1u)) continue;
    for (int j = 0; j < 8; ++j) {
      if (!(cand[1] >> j & 1u)) continue;
      for (int k = 0; k < 8; ++k) {
        if (!(cand[2] >> k & 1u)) continue;
        const int side[3] = {i, j, k};
        if (ball_on_sides(x, y, side, out)) return true;
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
  square_vertex_sides(x, y, cand);
  if ((cand[0] != first[0] || cand[1] != first[1] || cand[2] != first[2]) && ball_among(x, y, cand, out)) return true;
  const unsigned all[3] = {0xffu, 0xffu, 0xffu};
  return ball_among(x, y, all, out);
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
  // i.e. the point lies above their breakpoint; false on the breakpoint.
  template <typename Site>
  struct distance_predicate {
    template <typename Point>
    bool operator()(const Site& left, const Site& right, const Point& p) const {
      if (left.is_segment() || right.is_segment()) throw std::logic_error("sweep: segment sites not supported yet");
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

  // Three consecutive arcs (bottom to top) whose middle one will vanish: the points turn
  // clockwise (as in any convex distance) and a ball of N_eps passes through them.
  template <typename Site, typename Circle>
  struct circle_formation_predicate {
    bool operator()(const Site& s1, const Site& s2, const Site& s3, Circle& c) const {
      if (s1.is_segment() || s2.is_segment() || s3.is_segment())
        throw std::logic_error("sweep: segment sites not supported yet");
      if (orientation(s1.x(), s1.y(), s2.x(), s2.y(), s3.x(), s3.y()) >= 0) return false;
      const std::int64_t x[3] = {s1.x(), s2.x(), s3.x()}, y[3] = {s1.y(), s2.y(), s3.y()};
      Ball b;
      if (!ball_through(x, y, b)) return false;
      const Eps one_eps = Eps::of(1, 1);
      c = Circle(Ratio(b.cx, b.den), Ratio(b.cy, b.den), Ratio(b.cx * one_eps + b.r, b.den * one_eps));
      return true;
    }
  };
};

}  // namespace linf::sweep
