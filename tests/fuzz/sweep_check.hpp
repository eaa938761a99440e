// The sweep-line builder's diagram against the subdivision's, as two sets of pieces covering
// each other. Shared by the tests (tests/cpp/diagram/test_sweep.cpp) and the fuzzer.
//   - Every piece of the sweep lies, its whole length, within the allowance of the
//     subdivision's pieces with the same two owners.
//   - Every piece of the subdivision lies, its whole length, within the allowance of the
//     sweep's pieces that share an owner with it.
// The allowance at a point: `tol` relative to the point's size (a builder rounds both
// coordinates of a point at its scale: the subdivision gave y = 7.5e-9 for 0 at x = 3.8e8)
// plus `floor` (DBU: the subdivision's own allowance, which grows with the layer's box,
// builder.cpp's allowance()).
// Covering, not equal ends, because the subdivision decides within that allowance of the
// distance functions, not of the points: where two functions are nearly parallel it places
// their vertex the allowance over their gradients' difference away (6e-4 DBU along a diagonal
// beside an edge of slope 5e-5), its piece running on along the next bisector of its site. It
// may also leave a piece in two that just miss being collinear far from the origin, a short
// copy of part of a piece (a box's rounding of the same bisector), or where three sites tie
// along a line a region of no width between two of them: each lies on the sweep's pieces. The
// sweep's own pieces, the diagram under test, keep both owners.
// A piece of zero length (within the allowance) is a vertex, not a part of a bisector, and the
// vertex is there either way as the end of the pieces around it: it is not compared.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "linf/geometry/piece.hpp"

namespace linf::fuzz {

// The part [t0, t1] of the segment p + t (q - p), t in [0, 1], within L-inf distance d of the
// segment ab (the convex hull of the squares of half-side d at a and b); false if none.
inline bool part_near(const Vec2& p, const Vec2& q, const Vec2& a, const Vec2& b, double d, double& t0, double& t1) {
  Vec2 c[8];
  int n = 0;
  for (const Vec2& e : {a, b})
    for (double sx : {-d, d})
      for (double sy : {-d, d}) c[n++] = Vec2{e.x + sx, e.y + sy};
  std::sort(c, c + 8, [](const Vec2& u, const Vec2& v) { return u.x < v.x || (u.x == v.x && u.y < v.y); });
  auto cross = [](const Vec2& o, const Vec2& u, const Vec2& v) {
    return (u.x - o.x) * (v.y - o.y) - (u.y - o.y) * (v.x - o.x);
  };
  Vec2 h[16];  // Andrew's monotone chain, counter-clockwise
  int k = 0;
  for (int i = 0; i < 8; ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], c[i]) <= 0) --k;
    h[k++] = c[i];
  }
  for (int i = 6, lo = k + 1; i >= 0; --i) {
    while (k >= lo && cross(h[k - 2], h[k - 1], c[i]) <= 0) --k;
    h[k++] = c[i];
  }
  --k;  // the last point is the first
  // Cyrus-Beck: inside every edge's half-plane (left of it).
  t0 = 0, t1 = 1;
  const Vec2 dir{q.x - p.x, q.y - p.y};
  for (int i = 0; i < k; ++i) {
    const Vec2 &u = h[i], &v = h[(i + 1) % k];
    const double at_p = cross(u, v, p);                         // >= 0: p inside this edge
    const double rate = (v.x - u.x) * dir.y - (v.y - u.y) * dir.x;  // its change along dir
    if (rate == 0) {
      if (at_p < 0) return false;
      continue;
    }
    const double t = -at_p / rate;
    if (rate > 0) t0 = std::max(t0, t);
    else t1 = std::min(t1, t);
  }
  return t0 <= t1;
}

// "" if each side's pieces are covered as above; else the first piece that is not (its owners
// in `owners`, if given).
inline std::string same_pieces(const std::vector<Piece>& subdivision, const std::vector<Piece>& sweep, double tol,
                               double floor = 0, std::pair<int, int>* owners = nullptr) {
  auto allowance = [tol, floor](const Vec2& u) { return tol * (1 + std::max(std::fabs(u.x), std::fabs(u.y))) + floor; };
  auto point_like = [&](const Piece& x) {
    const double d = allowance(x.p);
    return std::fabs(x.p.x - x.q.x) <= d && std::fabs(x.p.y - x.q.y) <= d;
  };
  std::map<int, std::vector<const Piece*>> by_site;  // the sweep's pieces by each owner
  std::map<std::pair<int, int>, std::vector<const Piece*>> sub_by_pair;
  for (const Piece& y : sweep) by_site[y.a].push_back(&y), by_site[y.b].push_back(&y);
  for (const Piece& y : subdivision) sub_by_pair[{std::min(y.a, y.b), std::max(y.a, y.b)}].push_back(&y);
  // Whether the pieces ys cover x, within the allowance at x's larger end.
  auto covered = [&](const Piece& x, const std::vector<const Piece*>& ys, bool same_owners) {
    const double d = std::max(allowance(x.p), allowance(x.q));
    std::vector<std::pair<double, double>> parts;
    for (const Piece* y : ys) {
      if (same_owners && std::minmax(x.a, x.b) != std::minmax(y->a, y->b)) continue;
      double t0, t1;
      if (part_near(x.p, x.q, y->p, y->q, d, t0, t1)) parts.push_back({t0, t1});
    }
    std::sort(parts.begin(), parts.end());
    double reach = 0;
    for (const auto& [t0, t1] : parts) {
      if (t0 > reach) break;
      reach = std::max(reach, t1);
    }
    return reach >= 1;
  };
  auto report = [owners](const char* who, const Piece& x) {
    if (owners) *owners = {x.a, x.b};
    char m[300];
    std::snprintf(m, sizeof m, "only the %s has %d-%d (%.17g,%.17g)-(%.17g,%.17g)", who, x.a, x.b, x.p.x, x.p.y, x.q.x,
                  x.q.y);
    return std::string(m);
  };
  static const std::vector<const Piece*> none;
  for (const Piece& x : subdivision) {
    if (point_like(x)) continue;
    std::vector<const Piece*> ys;
    for (int s : {x.a, x.b}) {
      const auto it = by_site.find(s);
      if (it != by_site.end()) ys.insert(ys.end(), it->second.begin(), it->second.end());
    }
    if (!covered(x, ys, false)) return report("subdivision", x);
  }
  for (const Piece& x : sweep) {
    if (point_like(x)) continue;
    const auto it = sub_by_pair.find({std::min(x.a, x.b), std::max(x.a, x.b)});
    if (!covered(x, it == sub_by_pair.end() ? none : it->second, true)) return report("sweep", x);
  }
  return "";
}

}  // namespace linf::fuzz
