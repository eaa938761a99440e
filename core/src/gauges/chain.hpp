// One owner pair's pieces walked into stretch paths (stretch.cpp), and the vertex keys that
// join piece ends. Internal to the gauge stage; a header of its own so that the tests can hold
// the walk for few pieces against the general one.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <unordered_map>
#include <vector>

#include "linf/geometry/distance.hpp"
#include "linf/gauges/stretch.hpp"
#include "linf/util/round.hpp"

namespace linf::detail {

// Piece ends meet at exactly computed vertices up to rounding; a 1/1024 DBU grid joins them.
// (A struct, not a std::pair: the held ends and point stretches live in Paged arrays, which
// take only trivially copyable values.)
struct Key {
  long long x, y;
  bool operator==(const Key& o) const { return x == o.x && y == o.y; }
  bool operator<(const Key& o) const { return x < o.x || (x == o.x && y < o.y); }
};
inline Key key_of(const Vec2& v) { return {round_half_away(v.x * 1024.0), round_half_away(v.y * 1024.0)}; }

struct KeyHash {
  std::size_t operator()(const Key& k) const { return std::hash<long long>()(k.x * 1000003LL ^ k.y); }
};

inline double dist(const Vec2& a, const Vec2& b) { return std::hypot(a.x - b.x, a.y - b.y); }

// A piece's clearance is convex along it but not always linear: between two points on a
// diagonal the L-inf bisector dips from both ends to the middle. Convexity means the midpoint
// test finds every such dip; the dip's bottom is found by ternary search and becomes a path
// point, so that the path's linear profile holds the true minimum.
inline void refine(const Site& owner, const Vec2& u, const Vec2& v, double du, double dv, int depth, Stretches& out) {
  auto at = [&](double t) { return Vec2{u.x + t * (v.x - u.x), u.y + t * (v.y - u.y)}; };
  auto f = [&](double t) {
    const Vec2 p = at(t);
    return dist_site(p.x, p.y, owner);
  };
  const double tol = 1e-7 * (1.0 + std::max(du, dv));
  if (depth > 0 && f(0.5) < 0.5 * (du + dv) - tol) {
    double lo = 0, hi = 1;
    for (int i = 0; i < 100 && hi - lo > 1e-12; ++i) {
      const double a = lo + (hi - lo) / 3, b = hi - (hi - lo) / 3;
      (f(a) <= f(b) ? hi : lo) = (f(a) <= f(b) ? b : a);
    }
    const double t = 0.5 * (lo + hi), dt = f(t);
    refine(owner, u, at(t), du, dt, depth - 1, out);
    refine(owner, at(t), v, dt, dv, depth - 1, out);
    return;
  }
  out.add(v, dv);
}

// A piece's path points and length, walked from p to q (forward) or back.
inline void walk(const Sites& sites, const Piece& p, bool forward, Stretches& out) {
  const Vec2 u = forward ? p.p : p.q, v = forward ? p.q : p.p;
  const double du = forward ? p.d1 : p.d2, dv = forward ? p.d2 : p.d1;
  if (out.empty_path()) out.add(u, du);
  out.lengthen(dist(u, v));
  refine(sites.sites[p.a], u, v, du, dv, 3, out);
}

// chain_any() below for a pair of few pieces, as nearly all are: the same walk, over flat
// arrays instead of a hash map and a set (whose allocations were most of the stretches' time).
constexpr std::size_t kFewPieces = 32;
inline void chain_few(const Sites& sites, const Piece* pieces, const std::int32_t* ids, std::size_t n, Stretches& out) {
  std::int32_t real[kFewPieces];
  Key kp[kFewPieces], kq[kFewPieces];
  bool used[kFewPieces];
  std::size_t m = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const Piece& p = pieces[ids[k]];
    const Key u = key_of(p.p), v = key_of(p.q);
    if (u == v) continue;
    real[m] = ids[k], kp[m] = u, kq[m] = v, used[m] = false, ++m;
  }
  const Piece& first = pieces[ids[0]];
  const std::int32_t a = std::min(first.a, first.b), b = std::max(first.a, first.b);
  if (m == 0) {  // only degenerate pieces: one point
    out.open(a, b, first.kind);
    out.add(first.p, first.d1);
    return;
  }
  auto at = [&](std::size_t r, const Key& k) { return !used[r] && (kp[r] == k || kq[r] == k); };
  for (std::size_t left = m; left > 0;) {
    std::size_t start = 0;
    while (used[start]) ++start;
    Key from = kp[start];
    bool found = false;
    for (std::size_t r = 0; r < m && !found; ++r) {
      if (used[r]) continue;
      for (const Key& k : {kp[r], kq[r]}) {
        std::size_t deg = 0;
        for (std::size_t j = 0; j < m; ++j) deg += at(j, k);
        if (deg % 2 == 1) {
          start = r, from = k, found = true;
          break;
        }
      }
    }
    out.open(a, b, pieces[real[start]].kind);
    for (std::size_t cur = start, next;; cur = next) {
      used[cur] = true, --left;
      const bool forward = kp[cur] == from;
      walk(sites, pieces[real[cur]], forward, out);
      from = forward ? kq[cur] : kp[cur];
      for (next = 0; next < m && !at(next, from); ++next) {
      }
      if (next == m) break;
    }
  }
}

// Orders one owner pair's pieces into paths: start at an end of odd degree, walk while a
// continuation exists, repeat until every piece is used.
inline void chain_any(const Sites& sites, const Piece* pieces, const std::int32_t* ids, std::size_t n, Stretches& out) {
  std::unordered_map<Key, std::vector<std::int32_t>, KeyHash> at;
  std::vector<std::int32_t> real;
  for (std::size_t k = 0; k < n; ++k) {
    const std::int32_t i = ids[k];
    const Piece& p = pieces[i];
    if (key_of(p.p) == key_of(p.q)) continue;
    real.push_back(i);
    at[key_of(p.p)].push_back(i);
    at[key_of(p.q)].push_back(i);
  }
  const Piece& first = pieces[ids[0]];
  const std::int32_t a = std::min(first.a, first.b), b = std::max(first.a, first.b);
  if (real.empty()) {  // only degenerate pieces: one point
    out.open(a, b, first.kind);
    out.add(first.p, first.d1);
    return;
  }
  std::set<std::int32_t> unused(real.begin(), real.end());
  while (!unused.empty()) {
    // Prefer a start of odd degree so that an open chain is walked from one end.
    std::int32_t start = *unused.begin();
    Key from = key_of(pieces[start].p);
    for (std::int32_t i : unused) {
      const Piece& p = pieces[i];
      bool found = false;
      for (const Key& k : {key_of(p.p), key_of(p.q)}) {
        std::size_t deg = 0;
        for (std::int32_t j : at[k]) deg += unused.count(j);
        if (deg % 2 == 1) {
          start = i;
          from = k;
          found = true;
          break;
        }
      }
      if (found) break;
    }
    out.open(a, b, pieces[start].kind);
    std::int32_t cur = start;
    while (cur >= 0) {
      unused.erase(cur);
      const Piece& p = pieces[cur];
      const bool forward = key_of(p.p) == from;
      walk(sites, p, forward, out);
      from = key_of(forward ? p.q : p.p);
      cur = -1;
      for (std::int32_t j : at[from])
        if (unused.count(j)) {
          cur = j;
          break;
        }
    }
  }
}

// One owner pair's pieces ids[0..n) (ascending, at least one) as paths, appended to `out`.
inline void chain(const Sites& sites, const Piece* pieces, const std::int32_t* ids, std::size_t n, Stretches& out) {
  if (n <= kFewPieces) chain_few(sites, pieces, ids, n, out);
  else chain_any(sites, pieces, ids, n, out);
}

}  // namespace linf::detail
