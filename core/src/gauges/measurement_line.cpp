// The measurement line of a gauge: where a CD-SEM would measure the width or space the gauge
// stands for. The rule and its tie-breaks are in docs/design.md, "Gauge rules".
#include "linf/gauges/gauge.hpp"

#include "linf/geometry/distance.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>

namespace linf {

namespace {

// DBU. Gauge points are exact to far better; a contact closer than this to a corner of the
// gauge point's square is taken to be at the corner.
constexpr double kEps = 1e-6;

double coord(const Point& p, int k) { return k == 0 ? double(p.x) : double(p.y); }
double coord(const Vec2& p, int k) { return k == 0 ? p.x : p.y; }
Vec2 point(int k, double along, double other) { return k == 0 ? Vec2{along, other} : Vec2{other, along}; }

bool slanted(const Site& s) { return s.a.x != s.b.x && s.a.y != s.b.y; }

// An edge across axis k: the line along k meets it at one coordinate of k.
bool across(const Site& s, int k) { return !s.is_point() && coord(s.a, k) == coord(s.b, k); }

Vec2 euclid_nearest(const Site& s, const Vec2& p) {
  const double ax = double(s.a.x), ay = double(s.a.y);
  const double dx = double(s.b.x) - ax, dy = double(s.b.y) - ay;
  const double l2 = dx * dx + dy * dy;
  const double t = l2 > 0 ? std::clamp(((p.x - ax) * dx + (p.y - ay) * dy) / l2, 0.0, 1.0) : 0.0;
  return {ax + t * dx, ay + t * dy};
}

// A point of the site at the least L-inf distance from p (the only one for a slanted edge): the
// best of the breakpoints of the convex distance along the site, as in dist_segment.
Vec2 linf_nearest(const Site& s, const Vec2& p) {
  const double ax = double(s.a.x), ay = double(s.a.y);
  const double dx = double(s.b.x) - ax, dy = double(s.b.y) - ay;
  const double ux = p.x - ax, uy = p.y - ay;
  double best_t = 0, best = dist_point(ux, uy, 0, 0);
  auto consider = [&](double t) {
    t = std::clamp(t, 0.0, 1.0);
    const double v = std::max(std::fabs(ux - t * dx), std::fabs(uy - t * dy));
    if (v < best) best = v, best_t = t;
  };
  consider(1.0);
  if (dx != 0) consider(ux / dx);
  if (dy != 0) consider(uy / dy);
  if (dx - dy != 0) consider((ux - uy) / (dx - dy));
  if (dx + dy != 0) consider((ux + uy) / (dx + dy));
  return {ax + best_t * dx, ay + best_t * dy};
}

// Where a line along axis k meets an owner: at `along` on axis k, anywhere in [lo, hi] on the
// other axis. For an edge across k, or a vertex (which stands for its edges across k), that is
// the boundary within the gauge point's square; otherwise the owner's L-inf nearest point.
struct End {
  double along = 0, lo = 0, hi = 0;
  bool touches = false;  // on a side of the square across axis k: at L-inf distance d along k
  bool proper = false;   // there away from the square's corners: across an edge
  int side = 0;          // -1 or +1: which side along k
};

End end_on(const Sites& sites, std::int32_t id, const Vec2& c, double d, int k) {
  const int o = 1 - k;
  const Site& s = sites.sites[id];
  const double wlo = coord(c, o) - d, whi = coord(c, o) + d;
  End e;
  auto clip = [&](const Site& t) {
    const double lo = std::min(coord(t.a, o), coord(t.b, o)), hi = std::max(coord(t.a, o), coord(t.b, o));
    return std::pair<double, double>{std::max(lo, wlo), std::min(hi, whi)};
  };
  if (s.is_point()) {
    e.along = coord(s.a, k);
    e.lo = e.hi = coord(s.a, o);
    for (std::int32_t n : {s.end0, s.end1}) {
      if (n < 0 || !across(sites.sites[n], k)) continue;
      const auto [lo, hi] = clip(sites.sites[n]);
      if (lo <= hi) e.lo = std::min(e.lo, lo), e.hi = std::max(e.hi, hi);
    }
  } else if (across(s, k)) {
    e.along = coord(s.a, k);
    const auto [lo, hi] = clip(s);
    if (lo <= hi) {
      e.lo = lo, e.hi = hi;
    } else {  // beyond the square's reach across: its end nearest the gauge point
      e.lo = e.hi = std::clamp(coord(c, o), std::min(coord(s.a, o), coord(s.b, o)), std::max(coord(s.a, o), coord(s.b, o)));
    }
  } else {
    const Vec2 p = linf_nearest(s, c);
    e.along = coord(p, k);
    e.lo = e.hi = coord(p, o);
    if (!slanted(s)) return e;  // an edge along k is measured across the other axis
  }
  const double off = e.along - coord(c, k);
  e.touches = std::fabs(off) >= d - kEps && e.hi >= wlo - kEps && e.lo <= whi + kEps;
  e.proper = e.touches && e.hi > wlo + kEps && e.lo < whi - kEps;
  e.side = off < 0 ? -1 : 1;
  return e;
}

// The length of the owner's edges across axis k (a vertex stands for its edges).
double across_length(const Sites& sites, std::int32_t id, int k) {
  const Site& s = sites.sites[id];
  const std::int32_t edges[2] = {s.is_point() ? s.end0 : id, s.is_point() ? s.end1 : -1};
  double sum = 0;
  for (std::int32_t n : edges)
    if (n >= 0 && across(sites.sites[n], k))
      sum += std::fabs(coord(sites.sites[n].a, 1 - k) - coord(sites.sites[n].b, 1 - k));
  return sum;
}

// The axis the line runs along: one on whose opposite sides the gauge point's square touches
// the two owners; of two, the one with more owners touched away from a corner (across an
// edge), then the one across the longer owner edges, then x. None (the square touches them on
// two adjacent sides: a corner of one beside the other, offset both ways): the axis on which
// the owners' own L-inf distance is attained, ties x; the line is then that distance long.
int axis_of(const Sites& sites, const Gauge& g, const End (&ea)[2], const End (&eb)[2]) {
  int best = -1;
  double best_key[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    if (!ea[k].touches || !eb[k].touches || ea[k].side == eb[k].side) continue;
    const double key[2] = {double(ea[k].proper) + double(eb[k].proper),
                           across_length(sites, g.a, k) + across_length(sites, g.b, k)};
    if (best < 0 || key[0] > best_key[0] || (key[0] == best_key[0] && key[1] > best_key[1])) {
      best = k;
      best_key[0] = key[0], best_key[1] = key[1];
    }
  }
  if (best >= 0) return best;
  // The owners' own L-inf distance is attained at an end of one of them.
  const Site& sa = sites.sites[g.a];
  const Site& sb = sites.sites[g.b];
  double least = -1, dx = 0, dy = 0;
  auto consider = [&](const Point& e, const Site& other) {
    const Vec2 p{double(e.x), double(e.y)};
    const Vec2 q = linf_nearest(other, p);
    const double d = dist_point(p.x, p.y, q.x, q.y);
    if (least < 0 || d < least) least = d, dx = std::fabs(q.x - p.x), dy = std::fabs(q.y - p.y);
  };
  for (const Point& e : {sa.a, sa.b}) consider(e, sb);
  for (const Point& e : {sb.a, sb.b}) consider(e, sa);
  return dy > dx ? 1 : 0;
}

}  // namespace

MeasurementLine measurement_line(const Sites& sites, const Gauge& g) {
  const Site& sa = sites.sites[g.a];
  const Site& sb = sites.sites[g.b];
  // Two slanted edges: across them, Euclidean (perpendicular to two parallel 45-degree edges).
  if (slanted(sa) && slanted(sb)) return {euclid_nearest(sa, g.at), euclid_nearest(sb, g.at)};
  const double da = dist_site(g.at.x, g.at.y, sa), db = dist_site(g.at.x, g.at.y, sb);
  const End ea[2] = {end_on(sites, g.a, g.at, da, 0), end_on(sites, g.a, g.at, da, 1)};
  const End eb[2] = {end_on(sites, g.b, g.at, db, 0), end_on(sites, g.b, g.at, db, 1)};
  const int k = axis_of(sites, g, ea, eb);
  const End& a = ea[k];
  const End& b = eb[k];
  // Through the gauge point where both owners are there; else as near to it as both are; else
  // (corners offset both ways) in the gap between them, through the gauge point if it is there.
  const double c = coord(g.at, 1 - k);
  const double lo = std::max(a.lo, b.lo), hi = std::min(a.hi, b.hi);
  const double other = lo <= hi ? std::clamp(c, lo, hi) : std::clamp(c, hi, lo);
  return {point(k, a.along, other), point(k, b.along, other)};
}

}  // namespace linf
