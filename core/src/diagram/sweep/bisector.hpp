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
#pragma once
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>

#include "linf/geometry/site.hpp"

namespace linf::sweep {

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
    // Parallel: the middle line (collinear edges never share a region).
    along_y = !hs;
    mid_f = hs ? 0.5 * double(s.a.y + t.a.y) : 0.5 * double(s.a.x + t.a.x);
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

}  // namespace linf::sweep
