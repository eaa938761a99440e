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
#include <cstdint>
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

// The ball of N_eps through three points, if there is one: centre, radius and the sweep
// position at which the sweep line touches it. Each point lies on one side of the ball; for
// each choice of sides the centre solves a 3x3 linear system, and it is the ball only if the
// chosen side is the outermost for each point.
struct Ball {
  Eps cx, cy, r, den;  // centre (cx, cy) / den, radius r / den; den > 0
};

inline Eps det3(const Eps m[3][3]) {
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

inline bool ball_through(const std::int64_t x[3], const std::int64_t y[3], Ball& out) {
  const Side* S = sides();
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j)
      for (int k = 0; k < 8; ++k) {
        const Side* f[3] = {&S[i], &S[j], &S[k]};
        Eps m[3][3], h[3];
        for (int a = 0; a < 3; ++a) {
          m[a][0] = f[a]->alpha, m[a][1] = f[a]->beta, m[a][2] = Eps(-1);
          h[a] = f[a]->alpha * Eps(x[a]) + f[a]->beta * Eps(y[a]);
        }
        Eps d = det3(m);
        if (d.sign() == 0) continue;
        Eps col[3];
        Eps sol[3];
        for (int c = 0; c < 3; ++c) {
          Eps mc[3][3];
          for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b) mc[a][b] = b == c ? h[a] : m[a][b];
          sol[c] = det3(mc);
        }
        (void)col;
        if (d.sign() < 0) d = -d, sol[0] = -sol[0], sol[1] = -sol[1], sol[2] = -sol[2];
        bool ok = sol[2].sign() > 0;
        for (int a = 0; a < 3 && ok; ++a) {
          const Eps u = sol[0] - Eps(x[a]) * d, v = sol[1] - Eps(y[a]) * d;
          for (int s = 0; s < 8 && ok; ++s)
            if ((S[s].alpha * u + S[s].beta * v - sol[2]).sign() > 0) ok = false;
        }
        if (!ok) continue;
        out.cx = sol[0], out.cy = sol[1], out.r = sol[2], out.den = d;
        return true;
      }
  return false;
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
      Ratio ta, tb;
      const bool ra = arc_distance(a.x(), a.y(), p.x(), p.y(), ta);
      const bool rb = arc_distance(b.x(), b.y(), p.x(), p.y(), tb);
      if (!rb) return false;
      if (!ra) return true;
      return compare(tb, ta) < 0;
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
