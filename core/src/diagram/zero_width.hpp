// Points of no width between two segments: a segment and its own end are separated by the
// end's separator, the perpendicular axis line for an axis-parallel segment and the diagonal of
// the other sign of slope for any other (design.md, "The diagram's rules"). Two segments at a
// point with the same separator, on opposite sides of it, leave the point that line alone: a
// ray or two of no width, unless the other segments there close both. Both builders report the
// point's edges there as the edge of the two segments beside the ray (the sweep's relabelled,
// the subdivision's in collect()), so that their files agree.
// A ray's two segments are, on each side, the one nearest it in angle: where several segments
// on one side share the separator, the nearest is in front of the others all along the ray.
// The two rays of one point can so have different partners (a 45-degree edge in line with a
// second one, a third of slope 2/3 below the second: the ray above is the first two's, the ray
// below the first and the third's), hence a partner per ray.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <vector>

#include "linf/geometry/piece.hpp"
#include "linf/geometry/site.hpp"

namespace linf::detail {

// A segment's separator direction e at its ends (the same at both): (0, 1) for a horizontal
// segment, (1, 0) for a vertical one, (1, -1) for a positive slope, (1, 1) for a negative one.
inline std::array<int, 2> separator_of(const Site& s) {
  if (s.a.y == s.b.y) return {0, 1};
  if (s.a.x == s.b.x) return {1, 0};
  return {1, (s.b.x > s.a.x) == (s.b.y > s.a.y) ? -1 : 1};
}

// The side of its separator through its end `end` (0: a, 1: b) that segment s lies on: +1 left
// of e, -1 right of it.
inline int side_of(const Site& s, int end) {
  const std::array<int, 2> e = separator_of(s);
  const std::int64_t dx = (std::int64_t(s.b.x) - s.a.x) * (end == 0 ? 1 : -1);
  const std::int64_t dy = (std::int64_t(s.b.y) - s.a.y) * (end == 0 ? 1 : -1);
  return e[0] * dy - e[1] * dx > 0 ? 1 : -1;
}

// A segment's partners: [end][ray], the ray 0 along +e from that end, 1 along -e; -1 none.
using Partners = std::array<std::array<std::int32_t, 2>, 2>;

// For each site of S (points: none), its partners, by the ends' coordinates.
inline std::vector<Partners> zero_width_partners(const SiteList& S) {
  struct End {
    Coord x, y;
    std::int32_t seg;
    int end;
    std::int64_t dx, dy;  // the segment's direction from the place
    int ex, ey, side;     // its separator's direction, and the side of it the segment is on
  };
  std::vector<End> ends;
  for (std::size_t i = 0; i < S.size(); ++i) {
    const Site& s = S[i];
    if (s.is_point()) continue;
    const std::array<int, 2> e = separator_of(s);
    const std::int64_t dx = std::int64_t(s.b.x) - s.a.x, dy = std::int64_t(s.b.y) - s.a.y;
    for (int end = 0; end < 2; ++end)
      ends.push_back({end == 0 ? s.a.x : s.b.x, end == 0 ? s.a.y : s.b.y, std::int32_t(i), end, end == 0 ? dx : -dx,
                      end == 0 ? dy : -dy, e[0], e[1], side_of(s, end)});
  }
  std::sort(ends.begin(), ends.end(), [](const End& u, const End& v) { return std::tie(u.x, u.y, u.seg, u.end) < std::tie(v.x, v.y, v.seg, v.end); });
  std::vector<Partners> out(S.size(), Partners{{{-1, -1}, {-1, -1}}});
  for (std::size_t i = 0; i < ends.size();) {
    std::size_t j = i;
    while (j < ends.size() && ends[j].x == ends[i].x && ends[j].y == ends[i].y) ++j;
    for (std::size_t a = i; a < j; ++a) {
      const End& u = ends[a];
      for (int ray = 0; ray < 2; ++ray) {
        const int r = ray == 0 ? 1 : -1;  // the ray r e
        // The ray is the point's where no segment there has it on its own side of its separator.
        bool open = true;
        for (std::size_t k = i; k < j && open; ++k) {
          const End& z = ends[k];
          const std::int64_t c = z.ex * (r * u.ey) - z.ey * (r * u.ex);
          open = c == 0 || (c > 0 ? 1 : -1) != z.side;
        }
        if (!open) continue;
        // On each side of e, the segment with this separator nearest the ray in angle (ties, in
        // one direction, by the lower id). Side s: d1 is nearer +e than d2 where s (d1 x d2) > 0.
        const End* near[2] = {nullptr, nullptr};  // side -1, side +1
        for (std::size_t k = i; k < j; ++k) {
          const End& z = ends[k];
          if (z.ex != u.ex || z.ey != u.ey) continue;
          const End*& n = near[z.side > 0];
          if (!n) {
            n = &z;
            continue;
          }
          const __int128 cross = __int128(z.dx) * n->dy - __int128(z.dy) * n->dx;  // z x n
          const int nearer_plus_e = cross == 0 ? 0 : ((cross > 0) == (z.side > 0) ? 1 : -1);  // z nearer +e
          if (nearer_plus_e * r > 0 || (nearer_plus_e == 0 && z.seg < n->seg)) n = &z;
        }
        if (!near[0] || !near[1] || (near[0] != &u && near[1] != &u)) continue;
        const End& v = near[0] == &u ? *near[1] : *near[0];
        out[std::size_t(u.seg)][std::size_t(u.end)][std::size_t(ray)] = v.seg;
      }
    }
    i = j;
  }
  return out;
}

// The ray (0: +e, 1: -e) of segment s's separator from its end `end` that the piece p-q lies
// on, by whichever of p and q is farther from that end along e; -1 if both are at it.
inline int ray_of(const Site& s, int end, const Vec2& p, const Vec2& q) {
  const std::array<int, 2> e = separator_of(s);
  const Point& at = end == 0 ? s.a : s.b;
  auto along = [&](const Vec2& x) { return (x.x - double(at.x)) * e[0] + (x.y - double(at.y)) * e[1]; };
  const double tp = along(p), tq = along(q), t = std::fabs(tp) >= std::fabs(tq) ? tp : tq;
  return t > 0 ? 0 : t < 0 ? 1 : -1;
}

// The ray along which a half-edge of segment s that starts at its end `end` leaves it: s's
// cell lies on the left of its half-edges, on s's side of e.
inline int outward_ray(const Site& s, int end) { return side_of(s, end) > 0 ? 0 : 1; }

// The end of segment seg at the point site pt: 0 (a), 1 (b) or -1 (neither).
inline int end_at(const SiteList& S, std::int32_t seg, std::int32_t pt) {
  const Site& s = S[std::size_t(seg)];
  const Point& at = S[std::size_t(pt)].a;
  return s.a == at ? 0 : s.b == at ? 1 : -1;
}

// Segment seg's partner at its end `end` on the ray `ray`, or, with ray -1, the partner both
// rays have; -1 if none.
inline std::int32_t partner_at(const std::vector<Partners>& P, std::int32_t seg, int end, int ray) {
  const std::array<std::int32_t, 2>& o = P[std::size_t(seg)][std::size_t(end)];
  if (o[0] == o[1]) return o[0];
  return ray < 0 ? -1 : o[std::size_t(ray)];
}

}  // namespace linf::detail
