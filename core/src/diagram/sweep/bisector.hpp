// The bisector of two point sites under the ownership rule, as a function along one axis.
//
// For s and t with |dx| >= |dy| it is a function x(y): the perpendicular of the major axis
// through the midpoint, for y within (|dx| - |dy|) / 2 of the midpoint, and 45-degree rays
// beyond; with dy = 0 the ties of L-inf (the wedges above and below) go by L1, which is the
// whole perpendicular line. |dy| > |dx| is the same with the axes swapped.
#pragma once
#include <cmath>
#include <cstdint>

#include "linf/geometry/site.hpp"

namespace linf::sweep {

struct PointBisector {
  bool along_y;      // the parameter is y (x is the function of it); else the reverse
  double mid_p, mid_f;  // the midpoint in (parameter, function) coordinates
  double half;       // the straight middle part spans mid_p +- half
  double slope;      // d function / d parameter on the rays: -1, +1, or 0 (dx or dy = 0)

  PointBisector(const Point& s, const Point& t) {
    const std::int64_t dx = t.x - s.x, dy = t.y - s.y;
    along_y = std::llabs(dx) >= std::llabs(dy);
    const std::int64_t major = along_y ? dx : dy, minor = along_y ? dy : dx;
    mid_p = along_y ? 0.5 * double(s.y + t.y) : 0.5 * double(s.x + t.x);
    mid_f = along_y ? 0.5 * double(s.x + t.x) : 0.5 * double(s.y + t.y);
    half = 0.5 * double(std::llabs(major) - std::llabs(minor));
    slope = minor == 0 ? 0.0 : ((major > 0) == (minor > 0) ? -1.0 : 1.0);
  }
  double at(double p) const {
    if (p > mid_p + half) return mid_f + slope * (p - mid_p - half);
    if (p < mid_p - half) return mid_f + slope * (p - mid_p + half);
    return mid_f;
  }
  double param(const Vec2& v) const { return along_y ? v.y : v.x; }
  Vec2 point(double p) const { return along_y ? Vec2{at(p), p} : Vec2{p, at(p)}; }
  // Whether site s lies on the left of the bisector walked towards growing parameter.
  static bool left_of_growing(const Point& s, const Point& t) {
    const PointBisector b(s, t);
    const double sx = double(s.x), sy = double(s.y);
    // At the midpoint the curve runs along (slope, 1) (along y) or (1, slope) (along x).
    if (b.along_y) return (b.half > 0 || b.slope == 0 ? 0.0 : b.slope) * (sy - b.mid_p) - (sx - b.mid_f) > 0;
    return (sy - b.mid_f) - (b.half > 0 || b.slope == 0 ? 0.0 : b.slope) * (sx - b.mid_p) > 0;
  }
};

}  // namespace linf::sweep
