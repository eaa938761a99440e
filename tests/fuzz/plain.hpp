// Plain sites (voronoi_of_sites) must not cross: they may meet only at shared endpoints. The
// fuzzer's items are filtered to such a set, in exact integer arithmetic.
#pragma once
#include <algorithm>
#include <vector>

#include "linf/geometry/site.hpp"

namespace linf::fuzz {

// The side of the line ab that c lies on (coordinates may lie beyond 2^30 here).
inline int orientation(const Point& a, const Point& b, const Point& c) {
  const __int128 v = __int128(b.x - a.x) * (c.y - a.y) - __int128(b.y - a.y) * (c.x - a.x);
  return (v > 0) - (v < 0);
}

inline bool on_segment(const Point& p, const Segment& s) {
  return orientation(s.a, s.b, p) == 0 && std::min(s.a.x, s.b.x) <= p.x && p.x <= std::max(s.a.x, s.b.x) &&
         std::min(s.a.y, s.b.y) <= p.y && p.y <= std::max(s.a.y, s.b.y);
}

// Whether two items (segments, or points where a == b) meet elsewhere than at a shared endpoint
// (a point on an endpoint is that endpoint).
inline bool conflict(const Segment& s, const Segment& t) {
  const bool sp = s.a == s.b, tp = t.a == t.b;
  if (sp && tp) return false;
  if (sp || tp) {
    const Point& p = sp ? s.a : t.a;
    const Segment& g = sp ? t : s;
    return on_segment(p, g) && p != g.a && p != g.b;
  }
  const int o1 = orientation(s.a, s.b, t.a), o2 = orientation(s.a, s.b, t.b);
  const int o3 = orientation(t.a, t.b, s.a), o4 = orientation(t.a, t.b, s.b);
  const bool collinear_touch = on_segment(t.a, s) || on_segment(t.b, s) || on_segment(s.a, t) || on_segment(s.b, t);
  if (o1 * o2 > 0 || o3 * o4 > 0 || (o1 == 0 && o2 == 0 && !collinear_touch)) return false;
  for (const Point& p : {s.a, s.b})
    for (const Point& q : {t.a, t.b})
      if (p == q) {  // one shared endpoint: fine unless they overlap along a line
        const Point& u = p == s.a ? s.b : s.a;
        const Point& v = q == t.a ? t.b : t.a;
        return o1 == 0 && o2 == 0 && __int128(u.x - p.x) * (v.x - p.x) + __int128(u.y - p.y) * (v.y - p.y) > 0;
      }
  return true;
}

// The items in order, each kept unless it meets one kept before.
inline std::vector<Segment> non_crossing(const std::vector<Segment>& items) {
  std::vector<Segment> kept;
  for (const Segment& s : items)
    if (std::none_of(kept.begin(), kept.end(), [&](const Segment& t) { return conflict(s, t); })) kept.push_back(s);
  return kept;
}

}  // namespace linf::fuzz
