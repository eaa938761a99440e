// What a box tells about a site's distance function before any cell is cut: bounds over the
// box, and the box's quarters. Internal to the builder (subdivision.hpp).
#pragma once
#include <algorithm>
#include <array>
#include <cmath>

#include "affine.hpp"
#include "linf/geometry/piece.hpp"

// Internal linkage, as subdivision.hpp (see there).
namespace linf::detail {
namespace {

// The builder decides in coordinates relative to an integer origin at the centre of the
// sites' box (builder.cpp): its rounding then grows with the layout's extent, not with where
// the layout lies. A shape of 1 DBU near 2^30 was otherwise judged with allowances of 1e-3
// DBU, too coarse for its near-ties. Integer shifts are exact.
Site shifted(Site t, const Point& o) {
  t.a.x -= o.x, t.a.y -= o.y, t.b.x -= o.x, t.b.y -= o.y;
  return t;
}

Affine minus(const Affine& p, const Affine& q) { return {p.a - q.a, p.b - q.b, p.c - q.c}; }

// The largest value of a convex function over a box is at a corner.
double max_over(const DistFn& f, const Box& b) {
  return std::max({f.at(b.x1, b.y1), f.at(b.x2, b.y1), f.at(b.x2, b.y2), f.at(b.x1, b.y2)});
}

// A point or an axis-parallel edge is a box itself: its distances are the box-to-box ones.
bool rectilinear(const Site& s) { return s.a.x == s.b.x || s.a.y == s.b.y; }

// The largest L-inf (or L1) distance over box b of a rectilinear site, from the box's far
// sides: the value its distance function's pieces give at b's corners, exactly so (the
// coordinates are integers and their halves), without evaluating them.
double far_side(const Site& s, const Box& b, bool l1) {
  const double gx = std::max(b.x2 - double(std::max(s.a.x, s.b.x)), double(std::min(s.a.x, s.b.x)) - b.x1);
  const double gy = std::max(b.y2 - double(std::max(s.a.y, s.b.y)), double(std::min(s.a.y, s.b.y)) - b.y1);
  return l1 ? std::max(gx, 0.0) + std::max(gy, 0.0) : std::max(gx, gy);
}

// max_over of site s's own function fn (L-inf, or L1 if l1): the candidates' bound, for every
// site of every box.
double max_over(const DistFn& fn, const Site& s, const Box& b, bool l1) {
  return rectilinear(s) ? far_side(s, b, l1) : max_over(fn, b);
}

// The four quarters of a box, the subdivision step.
std::array<Box, 4> quarters(const Box& b) {
  const double mx = 0.5 * (b.x1 + b.x2), my = 0.5 * (b.y1 + b.y2);
  return {Box{b.x1, b.y1, mx, my}, Box{mx, b.y1, b.x2, my}, Box{b.x1, my, mx, b.y2}, Box{mx, my, b.x2, b.y2}};
}

// The two halves of a box across one axis: 1, the lower and the upper half; 2, the left and
// the right one.
std::array<Box, 2> halves(const Box& b, int axis) {
  if (axis == 1) {
    const double my = 0.5 * (b.y1 + b.y2);
    return {Box{b.x1, b.y1, b.x2, my}, Box{b.x1, my, b.x2, b.y2}};
  }
  const double mx = 0.5 * (b.x1 + b.x2);
  return {Box{b.x1, b.y1, mx, b.y2}, Box{mx, b.y1, b.x2, b.y2}};
}

// Liang-Barsky: the parameter interval [t0, t1] of the segment p + t (q - p), t in [0, 1],
// inside the closed box; false if the segment misses it.
bool clip_to_box(double px, double py, double qx, double qy, const Box& b, double& t0, double& t1) {
  t0 = 0, t1 = 1;
  const double dx = qx - px, dy = qy - py;
  auto edge = [&](double p, double q) {
    if (p == 0) return q >= 0;
    const double r = q / p;
    if (p < 0) { if (r > t1) return false; t0 = std::max(t0, r); }
    else { if (r < t0) return false; t1 = std::min(t1, r); }
    return true;
  };
  return edge(-dx, px - b.x1) && edge(dx, b.x2 - px) && edge(-dy, py - b.y1) && edge(dy, b.y2 - py);
}

// L-inf distance between a closed box and a site: zero if they meet, else attained at a vertex
// of one of them (both are convex polygons and the unit ball is a polygon).
// The same holds for L1, whose breakpoints along a segment are only the axis crossings.
double box_distance(const Box& b, const Site& s, bool l1 = false) {
  if (rectilinear(s)) {
    const double gx = std::max({b.x1 - double(std::max(s.a.x, s.b.x)), double(std::min(s.a.x, s.b.x)) - b.x2, 0.0});
    const double gy = std::max({b.y1 - double(std::max(s.a.y, s.b.y)), double(std::min(s.a.y, s.b.y)) - b.y2, 0.0});
    return l1 ? gx + gy : std::max(gx, gy);
  }
  auto point_to_box = [&](double x, double y) {
    const double ex = std::max({b.x1 - x, x - b.x2, 0.0}), ey = std::max({b.y1 - y, y - b.y2, 0.0});
    return l1 ? ex + ey : std::max(ex, ey);
  };
  const double ax = double(s.a.x), ay = double(s.a.y), bx = double(s.b.x), by = double(s.b.y);
  double d = std::min(point_to_box(ax, ay), point_to_box(bx, by));
  if (s.is_point() || d == 0) return d;
  double t0, t1;
  if (clip_to_box(ax, ay, bx, by, b, t0, t1)) return 0;
  const double dx = bx - ax, dy = by - ay;
  auto point_to_seg = [&](double x, double y) {
    const double ux = x - ax, uy = y - ay;
    auto f = [&](double t) {
      t = std::clamp(t, 0.0, 1.0);
      const double ex = std::fabs(ux - t * dx), ey = std::fabs(uy - t * dy);
      return l1 ? ex + ey : std::max(ex, ey);
    };
    double m = std::min(f(0), f(1));
    if (dx != 0) m = std::min(m, f(ux / dx));
    if (dy != 0) m = std::min(m, f(uy / dy));
    if (l1) return m;
    if (dx != dy) m = std::min(m, f((ux - uy) / (dx - dy)));
    if (dx != -dy) m = std::min(m, f((ux + uy) / (dx + dy)));
    return m;
  };
  d = std::min({d, point_to_seg(b.x1, b.y1), point_to_seg(b.x2, b.y1), point_to_seg(b.x2, b.y2),
                point_to_seg(b.x1, b.y2)});
  return d;
}

}  // namespace
}  // namespace linf::detail
