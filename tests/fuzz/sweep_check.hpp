// The sweep-line builder's diagram against the subdivision's: the same pieces, each with the
// same owners and ends (either way round) within `tol` of the other's (relative to the point's
// size) plus `floor` (DBU: the subdivision's own allowance, which grows with the layer's box,
// builder.cpp's allowance(); a vertex where nearly parallel distance functions cross is placed
// only that well, 3e-8 off at (8, 0) on a layer 6e4 wide). Shared by the tests
// (tests/cpp/diagram/test_sweep.cpp) and the fuzzer.
// A piece of zero length (within `tol`) is a vertex, not a part of a bisector: the subdivision may leave one
// where a cell's boundary turns on a vertex (two sites tie along no length), the sweep does not,
// and the vertex is there either way as the end of the pieces around it. So neither side's
// points are compared.
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

// "" if every piece of each side has its match on the other; else the first one that has not.
inline std::string same_pieces(const std::vector<Piece>& subdivision, const std::vector<Piece>& sweep, double tol,
                               double floor = 0) {
  // Relative to the point's size, not to each coordinate's: a builder rounds both coordinates
  // of a point at its scale (the subdivision gave y = 7.5e-9 for 0 at x = 3.8e8).
  auto near = [tol, floor](const Vec2& u, const Vec2& v) {
    const double d = tol * (1 + std::max(std::fabs(u.x), std::fabs(u.y))) + floor;
    return std::fabs(u.x - v.x) <= d && std::fabs(u.y - v.y) <= d;
  };
  auto same = [&](const Piece& x, const Piece& y) {
    return (near(x.p, y.p) && near(x.q, y.q)) || (near(x.p, y.q) && near(x.q, y.p));
  };
  // Far from the origin a builder's rounding can leave one straight edge in two pieces that
  // just miss being collinear (the subdivision's vertex of a 1/3-slope bisector near 2^30):
  // pieces of one pair meeting end to end within tol, the joint within tol of the line through
  // their outer ends, are compared as one.
  auto by_pair = [&](const std::vector<Piece>& v, std::vector<Piece>& store) {
    std::map<std::pair<int, int>, std::vector<Piece>> groups;
    for (const Piece& p : v)
      if (!near(p.p, p.q)) groups[{p.a, p.b}].push_back(p);
    for (auto& [pair, g] : groups) {
      for (bool merged = true; merged;) {
        merged = false;
        for (std::size_t i = 0; i < g.size() && !merged; ++i)
          for (std::size_t j = 0; j < g.size() && !merged; ++j) {
            if (i == j) continue;
            Piece x = g[i], y = g[j];
            if (near(x.p, y.p) || near(x.q, y.q)) std::swap(y.p, y.q);  // as x.q -> y.p or x.p -> y.q
            if (near(x.p, y.q)) std::swap(x, y);
            if (!near(x.q, y.p)) continue;
            // The joint within tol (at its scale, as near) of the line through the outer ends.
            const double ux = y.q.x - x.p.x, uy = y.q.y - x.p.y, wx = x.q.x - x.p.x, wy = x.q.y - x.p.y;
            const double len = std::hypot(ux, uy), scale = 1 + std::max(std::fabs(x.q.x), std::fabs(x.q.y));
            if (len == 0 || std::fabs(ux * wy - uy * wx) > (tol * scale + floor) * len || ux * wx + uy * wy <= 0 ||
                ux * wx + uy * wy >= len * len)
              continue;
            x.q = y.q;
            g[i] = x;
            g.erase(g.begin() + std::ptrdiff_t(j));
            merged = true;
          }
      }
      store.insert(store.end(), g.begin(), g.end());
    }
    std::map<std::pair<int, int>, std::vector<const Piece*>> m;
    for (const Piece& p : store) m[{p.a, p.b}].push_back(&p);
    return m;
  };
  std::vector<Piece> sa, sb;
  sa.reserve(subdivision.size()), sb.reserve(sweep.size());
  const auto a = by_pair(subdivision, sa), b = by_pair(sweep, sb);
  // Both ends of x within the allowance of the piece y (at x's end's scale, as near).
  auto on = [&](const Piece& x, const Piece& y) {
    auto close = [&](const Vec2& u) {
      const double dx = y.q.x - y.p.x, dy = y.q.y - y.p.y, l2 = dx * dx + dy * dy;
      const double t = l2 == 0 ? 0 : std::clamp(((u.x - y.p.x) * dx + (u.y - y.p.y) * dy) / l2, 0.0, 1.0);
      return near(u, Vec2{y.p.x + t * dx, y.p.y + t * dy});
    };
    return close(x.p) && close(x.q);
  };
  // The subdivision may also leave a short copy of part of a piece, a box's rounding of the
  // same bisector (1e-3 DBU along a corner of two steep edges, within 5e-7 of it): a piece of
  // the subdivision lying on a piece of the sweep's with the same owners is that piece. The
  // sweep's pieces must each have their equal.
  auto missing = [&](const decltype(a)& from, const decltype(a)& in, const char* who) -> std::string {
    const bool from_subdivision = &from == &a;
    for (const auto& [pair, pieces] : from) {
      const auto it = in.find(pair);
      for (const Piece* x : pieces) {
        bool found = false;
        if (it != in.end())
          for (const Piece* y : it->second) found = found || same(*x, *y) || (from_subdivision && on(*x, *y));
        // Where three sites tie along a line (two steep edges and their shared end, along the
        // end's diagonal) the subdivision may leave the middle one a region of no width, its
        // two sides on one line: a piece lying on a sweep piece with one owner in common.
        if (!found && from_subdivision)
          for (const auto& [other, ys] : in) {
            if (other.first != x->a && other.second != x->b && other.first != x->b && other.second != x->a) continue;
            for (const Piece* y : ys) found = found || on(*x, *y);
          }
        if (found) continue;
        char m[300];
        std::snprintf(m, sizeof m, "only the %s has %d-%d (%.17g,%.17g)-(%.17g,%.17g)", who, x->a, x->b, x->p.x, x->p.y,
                      x->q.x, x->q.y);
        return m;
      }
    }
    return "";
  };
  const std::string d = missing(a, b, "subdivision");
  return d.empty() ? missing(b, a, "sweep") : d;
}

}  // namespace linf::fuzz
