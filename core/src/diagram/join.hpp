// Raw pieces joined per owner pair: the builder cuts every Voronoi edge at box and cell sides,
// and the pieces of one pair that continue each other in a straight line become one. The
// result does not depend on the order the pieces came in, nor on how they were grouped.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <tuple>
#include <vector>

#include "linf/geometry/piece.hpp"
#include "util/parallel.hpp"

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
  // Ends within the builder's rounding of each other meet. Its allowance (builder.cpp) is
  // 1e-12 of the coordinates' scale and moves an end by up to a few of them (1/128 DBU near
  // 2^30), far less than a DBU: pieces that do not meet, however far from the origin, stay apart.
  auto close = [](const Vec2& p, const Vec2& q) {
    return std::fabs(p.x - q.x) <= 1e-11 * (1 + std::fabs(p.x)) && std::fabs(p.y - q.y) <= 1e-11 * (1 + std::fabs(p.y));
  };
  // Collinear: turning by at most 1e-9, or with the shorter piece's far end within a few units
  // in the last place of the coordinates (2e-15 of them, 9 ulp) of the other's line: a sweep
  // tile cuts a piece of slope 1/3 (45-degree sites) at its side with the other coordinate
  // rounded, and a short part of it near 2^30 then turns by more than 1e-9 (the fuzzer found
  // one 11 DBU long). Not more: a true bend 1e-4 DBU wide stays one far out
  // (Diagram.ShallowSegmentMovesWithItsInput).
  auto collinear = [](const Piece& x, const Piece& y) {
    const double ux = x.q.x - x.p.x, uy = x.q.y - x.p.y, vx = y.q.x - y.p.x, vy = y.q.y - y.p.y;
    const double cross = std::fabs(ux * vy - uy * vx), lu = std::hypot(ux, uy), lv = std::hypot(vx, vy);
    if (cross <= 1e-9 * lu * lv) return true;
    const double scale = 1 + std::max({std::fabs(x.p.x), std::fabs(x.p.y), std::fabs(x.q.x), std::fabs(x.q.y)});
    return cross <= 2e-15 * scale * std::max(lu, lv);
  };
  // Two cells can both have one Voronoi edge on their boundary (a sliver between two nearly
  // coincident cuts): the builder then cuts out a piece, or a part of it, twice. Such
  // collinear pieces that share more than an end are covered by one, their union; joined end
  // to end a piece and its own copy would leave nothing of it.
  auto inside = [](const Piece& x, const Vec2& v) {  // on x (as close), strictly between its ends
    const double ux = x.q.x - x.p.x, uy = x.q.y - x.p.y, wx = v.x - x.p.x, wy = v.y - x.p.y;
    const double s = wx * ux + wy * uy, ll = ux * ux + uy * uy;
    return s > 0 && s < ll && std::fabs(wx * uy - wy * ux) <= 1e-11 * (1 + std::fabs(v.x) + std::fabs(v.y)) * std::sqrt(ll);
  };
  auto overlap = [&](const Piece& x, const Piece& y) {
    const bool same = (close(x.p, y.p) && close(x.q, y.q)) || (close(x.p, y.q) && close(x.q, y.p));
    return same || inside(x, y.p) || inside(x, y.q) || inside(y, x.p) || inside(y, x.q);
  };
  auto cover = [](Piece& x, const Piece& y) {  // x becomes the union of both, along the longer one
    const double ux = x.q.x - x.p.x, uy = x.q.y - x.p.y, ll = ux * ux + uy * uy;
    const double vx = y.q.x - y.p.x, vy = y.q.y - y.p.y;
    if (vx * vx + vy * vy > ll) {
      // x is the shorter: a point far out, or a crumb of rounding at y's end whose own
      // direction is noise (a copy of a steep edge's corner 3e-8 long, sideways): along x
      // the union would be x again and y lost (a subdivision finding near 2^24).
      Piece u = y;
      const double sp = (x.p.x - u.p.x) * vx + (x.p.y - u.p.y) * vy, sq = (x.q.x - u.p.x) * vx + (x.q.y - u.p.y) * vy;
      const double mm = vx * vx + vy * vy;
      if (std::min(sp, sq) < 0) u.p = sp <= sq ? x.p : x.q, u.d1 = sp <= sq ? x.d1 : x.d2;
      if (std::max(sp, sq) > mm) u.q = sp <= sq ? x.q : x.p, u.d2 = sp <= sq ? x.d2 : x.d1;
      x.p = u.p, x.q = u.q, x.d1 = u.d1, x.d2 = u.d2;
      return;
    }
    const double sp = (y.p.x - x.p.x) * ux + (y.p.y - x.p.y) * uy, sq = (y.q.x - x.p.x) * ux + (y.q.y - x.p.y) * uy;
    const Vec2 lo = sp <= sq ? y.p : y.q, hi = sp <= sq ? y.q : y.p;
    const double dlo = sp <= sq ? y.d1 : y.d2, dhi = sp <= sq ? y.d2 : y.d1;
    if (std::min(sp, sq) < 0) x.p = lo, x.d1 = dlo;
    if (std::max(sp, sq) > ll) x.q = hi, x.d2 = dhi;
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
        const Piece& o = first[j];
        // Overlapping, or meeting end to end: the union, along cur. A copy of a part of cur
        // whose far end the builder rounded just off cur's line meets cur at an end too, and
        // joined end to end it would fold cur back (a subdivision finding: a piece emitted
        // twice along a steep edge's separator); its union with cur is cur.
        if (!overlap(cur, o) && !close(cur.q, o.p) && !close(cur.q, o.q) && !close(cur.p, o.p) && !close(cur.p, o.q))
          continue;
        cover(cur, o);
        used[j] = 1;
        grown = true;
      }
    }
    orient(cur);
    joined.push_back(cur);
  }
  std::sort(joined.begin(), joined.end(), piece_order);
}

// Joins pieces of the same two owners that continue each other in a straight line, in place
// over [first, last), and returns how many there are then, from first on: on a large layer the
// raw pieces are the builder's largest buffer, and a copy would double it. Joining parts first
// (a tile's) and then their union gives the same maximal runs.
inline std::size_t join_range(Piece* first, Piece* last) {
  std::sort(first, last, piece_order);
  const std::size_t n = std::size_t(last - first);
  std::size_t out = 0;  // pieces written so far; always <= g0, so writing never overtakes reading
  std::vector<char> used;
  std::vector<Piece> joined;
  for (std::size_t g0 = 0; g0 < n;) {
    std::size_t g1 = g0;
    while (g1 < n && first[g1].a == first[g0].a && first[g1].b == first[g0].b) ++g1;
    join_run(first + g0, first + g1, used, joined);
    for (const Piece& p : joined) first[out++] = p;
    g0 = g1;
  }
  return out;
}

// join_range over all of `in`. With more than one thread, the owner pairs below a pivot pair
// (split_at_sampled_median) and those from it on are sorted and joined side by side, and the
// second half's pieces moved down after the first's: the same pieces in the same order, still
// in place (a layer's final sort had been the tiles' one long wait on a single core).
inline void join_pieces(std::vector<Piece>& in, int threads = 1) {
  Piece* const begin = in.data();
  Piece* const end = begin + in.size();
  if (worker_count(2, threads) < 2 || in.size() < (std::size_t(1) << 16)) {
    in.resize(join_range(begin, end));
    return;
  }
  Piece* const mid = split_at_sampled_median(begin, end, [](const Piece& x, const Piece& y) {
    return std::make_pair(x.a, x.b) < std::make_pair(y.a, y.b);
  });
  std::size_t kept[2];
  parallel_for(2, threads, [&](unsigned, std::size_t k) { kept[k] = k == 0 ? join_range(begin, mid) : join_range(mid, end); });
  std::move(mid, mid + kept[1], begin + kept[0]);
  in.resize(kept[0] + kept[1]);
}

}  // namespace
}  // namespace linf::detail
