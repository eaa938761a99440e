// Raw pieces joined per owner pair: the builder cuts every Voronoi edge at box and cell sides,
// and the pieces of one pair that continue each other in a straight line become one. The
// result does not depend on the order the pieces came in, nor on how they were grouped.
#pragma once
#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

#include "linf/piece.hpp"

// Internal linkage, as subdivision.hpp (see there).
namespace linf::detail {
namespace {

// A total order of pieces: owner pair, then position. Workers deliver raw pieces in any
// order, the result must not depend on it.
inline bool piece_order(const Piece& x, const Piece& y) {
  return std::tie(x.a, x.b, x.p.x, x.p.y, x.q.x, x.q.y) < std::tie(y.a, y.b, y.p.x, y.p.y, y.q.x, y.q.y);
}

// One owner pair's pieces [first, last), sorted by piece_order, joined where they continue
// each other in a straight line; the runs go to `joined` in piece_order. The runs are the
// same however the pieces came in (joined per tile or not).
inline void join_run(const Piece* first, const Piece* last, std::vector<char>& used, std::vector<Piece>& joined) {
  auto close = [](const Vec2& p, const Vec2& q) {
    return std::fabs(p.x - q.x) <= 1e-7 * (1 + std::fabs(p.x)) && std::fabs(p.y - q.y) <= 1e-7 * (1 + std::fabs(p.y));
  };
  auto collinear = [](const Piece& x, const Piece& y) {
    const double ux = x.q.x - x.p.x, uy = x.q.y - x.p.y, vx = y.q.x - y.p.x, vy = y.q.y - y.p.y;
    return std::fabs(ux * vy - uy * vx) <= 1e-9 * std::hypot(ux, uy) * std::hypot(vx, vy);
  };
  const std::size_t n = std::size_t(last - first);
  used.assign(n, 0);
  joined.clear();
  for (std::size_t i = 0; i < n; ++i) {
    if (used[i]) continue;
    used[i] = 1;
    Piece cur = first[i];
    for (bool grown = true; grown;) {
      grown = false;
      for (std::size_t j = 0; j < n; ++j) {
        if (used[j] || !collinear(cur, first[j])) continue;
        Piece o = first[j];
        if (close(cur.q, o.q) || close(cur.p, o.p)) std::swap(o.p, o.q), std::swap(o.d1, o.d2);
        if (close(cur.q, o.p)) { cur.q = o.q; cur.d2 = o.d2; }
        else if (close(cur.p, o.q)) { cur.p = o.p; cur.d1 = o.d1; }
        else continue;
        used[j] = 1;
        grown = true;
      }
    }
    joined.push_back(cur);
  }
  std::sort(joined.begin(), joined.end(), piece_order);
}

// Joins pieces of the same two owners that continue each other in a straight line, in place:
// on a large layer the raw pieces are the builder's largest buffer, and a copy would double it.
// Joining parts first (a tile's) and then their union gives the same maximal runs.
inline void join_pieces(std::vector<Piece>& in) {
  std::sort(in.begin(), in.end(), piece_order);
  std::size_t out = 0;  // pieces written so far; always <= g0, so writing never overtakes reading
  std::vector<char> used;
  std::vector<Piece> joined;
  for (std::size_t g0 = 0; g0 < in.size();) {
    std::size_t g1 = g0;
    while (g1 < in.size() && in[g1].a == in[g0].a && in[g1].b == in[g0].b) ++g1;
    join_run(in.data() + g0, in.data() + g1, used, joined);
    for (const Piece& p : joined) in[out++] = p;
    g0 = g1;
  }
  in.resize(out);
}

}  // namespace
}  // namespace linf::detail
