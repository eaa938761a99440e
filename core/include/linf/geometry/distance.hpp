// L-infinity (and L1, for ties) distances from a point to a site. Used by the classifier and,
// independently of CGAL, by the checker.
#pragma once
#include <algorithm>
#include <cmath>

#include "linf/geometry/piece.hpp"
#include "linf/geometry/site.hpp"

namespace linf {

inline double dist_point(double x, double y, double px, double py) {
  return std::max(std::fabs(x - px), std::fabs(y - py));
}

// Distance to the closed segment [a,b]. The function of the segment parameter t is convex and
// piecewise linear, so its minimum sits at one of a handful of breakpoints; evaluating all of
// them is exact up to rounding and needs no case analysis.
inline double dist_segment(double x, double y, const Point& a, const Point& b) {
  const double ax = double(a.x), ay = double(a.y);
  const double dx = double(b.x) - ax, dy = double(b.y) - ay;
  // Axis-parallel, most of a layer's edges: how far the point lies beyond the segment along
  // it, and across it. The breakpoints would give the same minimum, a rounding less exact, at
  // the cost of divisions the checker makes six times a piece.
  if (dy == 0) return std::max(std::max({std::min(ax, ax + dx) - x, x - std::max(ax, ax + dx), 0.0}), std::fabs(y - ay));
  if (dx == 0) return std::max(std::max({std::min(ay, ay + dy) - y, y - std::max(ay, ay + dy), 0.0}), std::fabs(x - ax));
  const double ux = x - ax, uy = y - ay;
  auto f = [&](double t) {
    t = std::clamp(t, 0.0, 1.0);
    return std::max(std::fabs(ux - t * dx), std::fabs(uy - t * dy));
  };
  double best = std::min(f(0.0), f(1.0));
  if (dx != 0) best = std::min(best, f(ux / dx));
  if (dy != 0) best = std::min(best, f(uy / dy));
  if (dx - dy != 0) best = std::min(best, f((ux - uy) / (dx - dy)));
  if (dx + dy != 0) best = std::min(best, f((ux + uy) / (dx + dy)));
  return best;
}

inline double dist_site(double x, double y, const Site& s) {
  return s.is_point() ? dist_point(x, y, double(s.a.x), double(s.a.y)) : dist_segment(x, y, s.a, s.b);
}

// L1 distance, the ownership rule's first tie-break; breakpoints are the axis crossings.
inline double dist_site_l1(double x, double y, const Site& s) {
  if (!s.is_point() && s.a.x != s.b.x && s.a.y != s.b.y &&
      std::llabs(std::int64_t(s.b.x) - s.a.x) != std::llabs(std::int64_t(s.b.y) - s.a.y))
    return std::max(std::fabs(x - double(s.a.x)) + std::fabs(y - double(s.a.y)),
                    std::fabs(x - double(s.b.x)) + std::fabs(y - double(s.b.y)));
  const double ax = double(s.a.x), ay = double(s.a.y);
  const double dx = double(s.b.x) - ax, dy = double(s.b.y) - ay;
  const double ux = x - ax, uy = y - ay;
  auto f = [&](double t) {
    t = std::clamp(t, 0.0, 1.0);
    return std::fabs(ux - t * dx) + std::fabs(uy - t * dy);
  };
  double best = std::min(f(0.0), f(1.0));
  if (dx != 0) best = std::min(best, f(ux / dx));
  if (dy != 0) best = std::min(best, f(uy / dy));
  return best;
}

}  // namespace linf
