// An oracle for small diagrams, by brute force over every site: a piece may end only where its
// edge ends. Just beyond a piece's end, on either side of its line, the owners (by the
// ownership rule: L-inf, then L1, then point before segment, then index) must not be its two
// owners again; if they are, the edge goes on and a piece is missing. The checker's random
// pairs found a 2-DBU gap in one piece only by chance; this looks at every end.
//
// Not judged: ends on the clip box, ends at a site (clearance 0), ends shared with another piece
// of the same pair (a bend of the bisector), ends too close to their own piece's other end or to
// a site to step beyond, points where a site is within the allowance of the owner without
// tying it exactly, and ends where a third site is as near as the pair just beyond (its region
// may be a wedge thinner than the samples' angle): too close to call.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "linf/geometry/distance.hpp"
#include "linf/geometry/piece.hpp"

namespace linf::fuzz {

struct EndsReport {
  std::size_t ends = 0, judged = 0;
  std::string failure;  // empty: none found
};

inline EndsReport check_piece_ends(const Diagram& d) {
  EndsReport rep;
  const auto& S = d.sites.sites;
  if (S.size() < 2) return rep;
  // Relative to the centre of the sites' box, as the builder: rounding then follows the extent.
  Coord x1 = S[0].a.x, y1 = S[0].a.y, x2 = x1, y2 = y1;
  for (const Site& s : S)
    for (const Point& p : {s.a, s.b}) x1 = std::min(x1, p.x), x2 = std::max(x2, p.x), y1 = std::min(y1, p.y), y2 = std::max(y2, p.y);
  const Coord ox = (x1 + x2) / 2, oy = (y1 + y2) / 2;
  const double extent = std::max<double>(1.0, double(std::max(x2 - x1, y2 - y1)));
  std::vector<Site> L;
  L.reserve(S.size());
  for (const Site& s : S) {
    Site t = s;
    t.a.x -= ox, t.a.y -= oy, t.b.x -= ox, t.b.y -= oy;
    L.push_back(t);
  }
  const double tol = 1e-8 * extent + 1e-9;
  const Box clip{d.clip.x1 - double(ox), d.clip.y1 - double(oy), d.clip.x2 - double(ox), d.clip.y2 - double(oy)};
  auto local = [&](const Vec2& v) { return Vec2{v.x - double(ox), v.y - double(oy)}; };
  auto near = [&](const Vec2& u, const Vec2& v) { return std::max(std::fabs(u.x - v.x), std::fabs(u.y - v.y)) <= 10 * tol; };

  // -1: site c comes before s at the point (dist, l1 of each), 1: after, 0: too close to call.
  auto order = [&](double dc, double lc, int c, double ds, double ls, int s, double scale) {
    const double exact = 1e-12 * (1 + std::max(dc, ds)) + 1e-15 * scale;
    if (dc < ds - tol) return -1;
    if (dc > ds + tol) return 1;
    if (std::fabs(dc - ds) > exact) return 0;
    const double exact1 = 1e-12 * (1 + std::max(lc, ls)) + 1e-15 * scale;
    if (lc < ls - tol) return -1;
    if (lc > ls + tol) return 1;
    if (std::fabs(lc - ls) > exact1) return 0;
    const bool pc = L[c].is_point(), ps = L[s].is_point();
    if (pc != ps) return pc ? -1 : 1;
    return c < s ? -1 : 1;
  };

  // The owner at x by the rule, or -1 where a site is within the allowance of it (not exactly
  // tied): too close to call.
  struct Owner { int site = -1; };
  auto owner = [&](const Vec2& x) {
    const double scale = std::fabs(x.x) + std::fabs(x.y);
    std::vector<double> dl(L.size());
    double least = INFINITY;
    for (std::size_t c = 0; c < L.size(); ++c) least = std::min(least, dl[c] = dist_site(x.x, x.y, L[c]));
    int best = -1;
    double bd = 0, bl = 0;
    std::vector<int> near_best;
    for (std::size_t c = 0; c < L.size(); ++c) {
      if (dl[c] > least + tol) continue;
      near_best.push_back(int(c));
      const double lc = dist_site_l1(x.x, x.y, L[c]);
      if (best < 0 || order(dl[c], lc, int(c), bd, bl, best, scale) < 0) best = int(c), bd = dl[c], bl = lc;
    }
    for (int c : near_best)
      if (c != best && order(dl[c], dist_site_l1(x.x, x.y, L[c]), c, bd, bl, best, scale) == 0) return Owner{};
    return Owner{best};
  };

  for (std::size_t i = 0; i < d.pieces.size(); ++i) {
    const Piece& pc = d.pieces[i];
    const Vec2 p = local(pc.p), q = local(pc.q);
    const double len = std::hypot(q.x - p.x, q.y - p.y);
    if (len <= 1e3 * tol) continue;
    for (int end = 0; end < 2; ++end) {
      ++rep.ends;
      const Vec2 e = end ? q : p, o = end ? p : q;
      const double clearance = end ? pc.d2 : pc.d1;
      if (clearance <= 10 * tol) continue;
      if (std::fabs(e.x - clip.x1) <= 10 * tol || std::fabs(e.x - clip.x2) <= 10 * tol ||
          std::fabs(e.y - clip.y1) <= 10 * tol || std::fabs(e.y - clip.y2) <= 10 * tol)
        continue;
      // A bend of the pair's bisector (another piece of the pair starts here), and the nearest
      // vertex elsewhere: the step beyond must stop short of it, or it may cross a third
      // site's sliver of a region and land where the pair's edge goes on again.
      bool bend = false;
      double nearest = INFINITY;
      for (std::size_t j = 0; j < d.pieces.size() && !bend; ++j) {
        const Piece& r = d.pieces[j];
        for (const Vec2& v : {local(r.p), local(r.q)})
          if (!near(v, e)) nearest = std::min(nearest, std::hypot(v.x - e.x, v.y - e.y));
        if (j == i || std::min(r.a, r.b) != std::min(pc.a, pc.b) || std::max(r.a, r.b) != std::max(pc.a, pc.b)) continue;
        bend = near(local(r.p), e) || near(local(r.q), e);
      }
      if (bend) continue;
      const double step = std::min(1e-2 * std::min(len, clearance), 0.25 * nearest);
      // Beyond the end, on either side of the piece's line and close to it (a thin wedge of a
      // third site may start at the end): the owners there.
      const double side = std::max(1e-3 * step, 50 * tol);
      if (side > 0.1 * step) continue;
      const Vec2 x{e.x + step * (e.x - o.x) / len, e.y + step * (e.y - o.y) / len};
      const Vec2 n{-side * (e.y - o.y) / len, side * (e.x - o.x) / len};
      const Owner left = owner({x.x + n.x, x.y + n.y}), right = owner({x.x - n.x, x.y - n.y});
      if (left.site < 0 || right.site < 0) continue;  // too close to call
      const bool same = (left.site == pc.a && right.site == pc.b) || (left.site == pc.b && right.site == pc.a);
      // A third site as near as the pair at x, within what the sideways step can change (an
      // L-inf distance moves by at most the step): its region may be a wedge starting at the
      // end and thinner than the samples' angle, passing between them. Too close to call.
      const double pair = std::max(dist_site(x.x, x.y, L[pc.a]), dist_site(x.x, x.y, L[pc.b]));
      bool wedge = false;
      for (std::size_t c = 0; c < L.size() && same && !wedge; ++c)
        wedge = int(c) != pc.a && int(c) != pc.b && dist_site(x.x, x.y, L[c]) <= pair + 2 * side + tol;
      if (wedge) continue;
      ++rep.judged;
      if (!same) continue;
      std::ostringstream m;
      m.precision(12);
      m << "piece " << pc.a << "-" << pc.b << " ends at (" << pc.p.x + (end ? pc.q.x - pc.p.x : 0) << ","
        << pc.p.y + (end ? pc.q.y - pc.p.y : 0) << ") but its owners still own either side " << step
        << " DBU beyond it";
      rep.failure = m.str();
      return rep;
    }
  }
  return rep;
}

}  // namespace linf::fuzz
