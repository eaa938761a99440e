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
// Points and segments of any slope (sweep.hpp); the balls of the circle events are ball.hpp's.
#pragma once
#include <boost/polygon/detail/voronoi_structures.hpp>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "diagram/sweep/ball.hpp"
#include "diagram/sweep/circle.hpp"
#include "diagram/sweep/eps.hpp"

namespace linf::sweep {

// I: the coefficients' type (eps.hpp): int64 where every segment is axis-parallel or at 45
// degrees, Int256 where one is slanted otherwise.
template <typename I>
struct CoordinateTraits {
  typedef std::int32_t int_type;
  typedef RatioT<I> fpt_type;
};


// How far left of `p` (on its horizontal) the arc of point site s lies when the sweep is at
// p.x: the root t of N_eps(p.x - t - s.x, p.y - s.y) = (1 + eps) t. N_eps is the largest of
// its sides' forms and each form's equation falls in t, so the root is the largest of their
// roots; the sides facing left (alpha = -(1 + eps)) have none unless p.x = s.x.
// Returns false where the arc does not reach p's height (p.x = s.x, p.y != s.y).
template <typename I>
bool arc_distance(std::int64_t sx, std::int64_t sy, std::int64_t px, std::int64_t py, RatioT<I>& t) {
  const std::int64_t dx = px - sx, dy = py - sy;
  if (dx == 0) {
    t = RatioT<I>(I(0));
    return dy == 0;
  }
  const EpsT<I> one_eps = EpsT<I>::of(I(1), I(1));
  bool any = false;
  for (int k = 0; k < 8; ++k) {
    const SideT<I>& f = sides<I>()[k];
    if (k == 2 || k == 3) continue;
    const RatioT<I> r(I(dx) * f.alpha + I(dy) * f.beta, one_eps + f.alpha);
    if (!any || compare(r, t) > 0) t = r, any = true;
  }
  return true;
}

// Whether the arc of point site b lies nearer p (on p's horizontal) than that of a: the
// sign of t_a - t_b. At eps = 0, t = max(dx / 2, |dy|); only its ties need the eps terms.
template <typename I>
int arc_nearer(std::int64_t ax, std::int64_t ay, std::int64_t bx, std::int64_t by, std::int64_t px,
                      std::int64_t py) {
  const bool reach_a = px != ax || py == ay, reach_b = px != bx || py == by;
  if (!reach_a || !reach_b) return reach_a == reach_b ? 0 : (reach_b ? 1 : -1);
  const std::int64_t ta = std::max<std::int64_t>(px - ax, 2 * std::llabs(py - ay));
  const std::int64_t tb = std::max<std::int64_t>(px - bx, 2 * std::llabs(py - by));
  if (ta != tb) return ta > tb ? 1 : -1;
  RatioT<I> ra, rb;
  arc_distance<I>(ax, ay, px, py, ra);
  arc_distance<I>(bx, by, px, py, rb);
  return compare(ra, rb);
}

template <typename I>
struct Predicates {
  using Ratio = RatioT<I>;
  using Eps = EpsT<I>;
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
    // Circle events by their keys (circle.hpp), exactly where the keys are too close to tell.
    bool operator()(const Site& l, const Circle& r) const {
      const int f = filtered_limits(double(l.x0()), r.lower_x_key());
      return (f != 0 ? f : compare(Ratio(I(l.x0())), r.lower_x())) < 0;
    }
    bool operator()(const Circle& l, const Site& r) const {
      const int f = filtered_limits(l.lower_x_key(), double(r.x0()));
      return (f != 0 ? f : compare(l.lower_x(), Ratio(I(r.x0())))) < 0;
    }
    bool operator()(const Circle& l, const Circle& r) const {
      int c = filtered_limits(l.lower_x_key(), r.lower_x_key());
      if (c == 0) c = compare(l.lower_x(), r.lower_x());
      if (c != 0) return c < 0;
      c = filtered_limits(l.y_key(), r.y_key());
      return (c != 0 ? c : compare(l.y(), r.y())) < 0;
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
      return arc_nearer<I>(a.x(), a.y(), b.x(), b.y(), p.x(), p.y()) > 0;
    }

    // t of a segment's arc (its line's) at p's height, the sweep at p.x; negative where p is on
    // the other side of the line than the arc (as Boost's signed distance): that arc is never
    // met there.
    template <typename Point>
    static Ratio segment_arc(const Site& s, const Point& p) {
      if (s.x0() == s.x1()) return Ratio(Eps(I(std::int64_t(p.x()) - s.x0())), Eps(I(2)));
      if (s.y0() != s.y1()) return diagonal_arc(s, p);
      const std::int64_t dy = std::int64_t(p.y()) - s.y0();
      return Ratio(I(s.x1() > s.x0() ? -dy : dy));  // the arc is on the right of point0 -> point1
    }

    // A slanted line lying in direction n from its arc (segment_normal): at q = p - (t, 0) the
    // N_eps distance to it is (1 + 2 eps) w(q) / |n|_1, w = n . (point0 - q) (ball.hpp: the
    // diagonal vertex touches), so t = (1 + 2 eps) w(p) / (|n|_1 (1 + eps) - n_x (1 + 2 eps)),
    // whose denominator is positive (|n_x| < |n|_1). At 45 degrees: w(p) (1 + 2 eps), or over
    // 3 + 4 eps.
    static Eps arc_den(const Normal& n) { return Eps::of(I(n.l1() - n.x), I(n.l1() - 2 * n.x)); }
    template <typename Point>
    static Ratio diagonal_arc(const Site& s, const Point& p) {
      const Normal n = segment_normal(s);
      const I w = I(n.x) * I(std::int64_t(s.x0()) - p.x()) + I(n.y) * I(std::int64_t(s.y0()) - p.y());
      return Ratio(Eps::of(w, I(2) * w), arc_den(n));
    }
    // d t / d y of that arc: -n_y (1 + 2 eps) over the same denominator.
    static Ratio diagonal_arc_slope(const Site& s) {
      const Normal n = segment_normal(s);
      return Ratio(Eps::of(I(-n.y), I(-2 * n.y)), arc_den(n));
    }

    // A point P and a 45-degree segment S, p on S's arc side. Boost's shortcuts for this case
    // are Euclidean; this is the rule they stand for. t_P(y) (arc_distance) is the largest of
    // linear functions of y, t_S(y) is linear, so E = t_S - t_P is concave and P's arc is in
    // front (E > 0) on one interval (y_lo, y_hi): the beach line reads S, P, S upwards, the
    // node (P, S) is the crossing at y_hi, (S, P) the one at y_lo. Where E <= 0, the sign of E's
    // slope just above p.y (t_S's less the largest slope among the sides attaining t_P) tells
    // whether the interval lies above p (rising) or below it. No slope is 0: no side of N_eps is
    // parallel to a line through two integer points.
    template <typename Point>
    static bool diagonal_ps(const Site& point, const Site& seg, const Point& p, bool reverse) {
      const std::int64_t dx = std::int64_t(p.x()) - point.x0(), dy = std::int64_t(p.y()) - point.y0();
      if (dx == 0) return dy > 0;  // P's arc is the ray at its own height: y_lo = y_hi = P.y
      const Eps one_eps = Eps::of(I(1), I(1));
      Ratio tp, slope;
      bool any = false;
      for (int k = 0; k < 8; ++k) {
        if (k == 2 || k == 3) continue;  // facing left: no root
        const SideT<I>& f = sides<I>()[k];
        const Ratio r(I(dx) * f.alpha + I(dy) * f.beta, one_eps + f.alpha), m(f.beta, one_eps + f.alpha);
        const int c = any ? compare(r, tp) : 1;
        if (c > 0) tp = r, slope = m, any = true;
        else if (c == 0 && compare(m, slope) > 0) slope = m;
      }
      const int e = compare(segment_arc(seg, p), tp);  // the sign of E at p.y
      if (e > 0) return reverse;                       // inside: above y_lo, below y_hi
      const bool rising = compare(diagonal_arc_slope(seg), slope) > 0;
      if (rising) return false;                        // below the interval (or at y_lo)
      return e < 0 || reverse;                         // above it; at y_hi: on (P, S)'s crossing
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
      if (seg.x0() != seg.x1() && seg.y0() != seg.y1()) {
        if (orientation(seg.x0(), seg.y0(), seg.x1(), seg.y1(), p.x(), p.y()) != -1)  // not on its arc's side
          return !seg.is_inverse();
        return diagonal_ps(point, seg, p, reverse);
      }
      const int fast = fast_ps(point, seg, p, reverse);
      if (fast != kUndefined) return fast == kLess;
      Ratio tp;
      const bool reach = arc_distance<I>(point.x0(), point.y0(), p.x(), p.y(), tp);
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
      Normal nrm[3];
      Span spans[3];
      for (int a = 0; a < 3; ++a) {
        const Site& t = *s[a];
        x[a] = t.x0(), y[a] = t.y0();
        fixed[a] = t.is_segment() ? segment_side(t) : -1;
        if (t.is_segment()) nrm[a] = segment_normal(t);
        if (t.is_segment())  // x, but y for a vertical segment
          spans[a] = t.x0() != t.x1() ? Span{std::min<std::int64_t>(t.x0(), t.x1()), std::max<std::int64_t>(t.x0(), t.x1())}
                                      : Span{std::min<std::int64_t>(t.y0(), t.y1()), std::max<std::int64_t>(t.y0(), t.y1())};
      }
      BallT<I> b;
      if (segments == 0 ? !ball_through<I>(x, y, b) : !ball_touching<I>(x, y, fixed, nrm, spans, b)) return false;
      c = Circle(b.cx, b.cy, b.r, b.den);
      // Boost's last test: a vertical segment's arc ends at its endpoints' heights.
      for (const Site* t : s) {
        if (!t->is_segment() || t->x0() != t->x1()) continue;
        const std::int64_t lo = std::min(t->y0(), t->y1()), hi = std::max(t->y0(), t->y1());
        if (compare(c.y(), Ratio(I(lo))) < 0 || compare(c.y(), Ratio(I(hi))) > 0) return false;
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
