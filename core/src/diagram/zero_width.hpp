// Points of no width between two segments: a segment and its own end are separated by the
// end's separator, the perpendicular axis line for an axis-parallel segment and the diagonal of
// the other sign of slope for any other (design.md, "The diagram's rules"). Two segments at a
// point with the same separator, on opposite sides of it, leave the point that line alone: a
// ray or two of no width, unless the other segments there close both. Both builders report the
// point's edges there as the two segments' edge (the sweep's relabelled, the subdivision's in
// collect()), so that their files agree.
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <tuple>
#include <vector>

#include "linf/geometry/site.hpp"

namespace linf::detail {

// For each site of S, the partner segment at its end a and at its end b (-1: none; points:
// none), by the ends' coordinates.
inline std::vector<std::array<std::int32_t, 2>> zero_width_partners(const SiteList& S) {
  struct End {
    Coord x, y;
    std::int32_t seg;
    int end;
    std::int64_t dx, dy;  // the segment's direction from the place
    int ex, ey, side;     // its separator's direction, and the side of it the segment is on
  };
  std::vector<End> ends;
  auto end_of = [](const Point& at, std::int32_t seg, int end, std::int64_t dx, std::int64_t dy) {
    End e{at.x, at.y, seg, end, dx, dy, 0, 0, 0};
    if (dy == 0) e.ex = 0, e.ey = 1;
    else if (dx == 0) e.ex = 1, e.ey = 0;
    else e.ex = 1, e.ey = (dx > 0) == (dy > 0) ? -1 : 1;
    e.side = e.ex * dy - e.ey * dx > 0 ? 1 : -1;
    return e;
  };
  for (std::size_t i = 0; i < S.size(); ++i) {
    const Site& s = S[i];
    if (s.is_point()) continue;
    const std::int64_t dx = std::int64_t(s.b.x) - s.a.x, dy = std::int64_t(s.b.y) - s.a.y;
    ends.push_back(end_of(s.a, std::int32_t(i), 0, dx, dy));
    ends.push_back(end_of(s.b, std::int32_t(i), 1, -dx, -dy));
  }
  std::sort(ends.begin(), ends.end(), [](const End& u, const End& v) { return std::tie(u.x, u.y, u.seg, u.end) < std::tie(v.x, v.y, v.seg, v.end); });
  std::vector<std::array<std::int32_t, 2>> out(S.size(), {-1, -1});
  for (std::size_t i = 0; i < ends.size();) {
    std::size_t j = i;
    while (j < ends.size() && ends[j].x == ends[i].x && ends[j].y == ends[i].y) ++j;
    for (std::size_t a = i; a < j; ++a)
      for (std::size_t b = a + 1; b < j; ++b) {
        const End &u = ends[a], &v = ends[b];
        if (u.ex != v.ex || u.ey != v.ey || u.side == v.side) continue;
        // A ray +-e of the line is the point's where every other segment's side of its own
        // separator leaves it (on the line, or on the other side).
        bool open = false;
        for (int r = -1; r <= 1 && !open; r += 2) {
          bool in = true;
          for (std::size_t k = i; k < j && in; ++k) {
            if (k == a || k == b) continue;
            const End& z = ends[k];
            const std::int64_t c = z.ex * (r * u.ey) - z.ey * (r * u.ex);
            in = c == 0 || (c > 0 ? 1 : -1) != z.side;
          }
          open = in;
        }
        if (!open) continue;
        out[u.seg][u.end] = v.seg, out[v.seg][v.end] = u.seg;
      }
    i = j;
  }
  return out;
}

}  // namespace linf::detail
