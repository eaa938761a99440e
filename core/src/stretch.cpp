#include "linf/stretch.hpp"

#include "linf/distance.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <unordered_map>
#include <utility>

namespace linf {

namespace {

// Piece ends meet at exactly computed vertices up to rounding; a 1/1024 DBU grid joins them.
using Key = std::pair<long long, long long>;
Key key_of(const Vec2& v) { return {std::llround(v.x * 1024.0), std::llround(v.y * 1024.0)}; }

struct KeyHash {
  std::size_t operator()(const Key& k) const { return std::hash<long long>()(k.first * 1000003LL ^ k.second); }
};

double dist(const Vec2& a, const Vec2& b) { return std::hypot(a.x - b.x, a.y - b.y); }

// A piece's clearance is convex along it but not always linear: between two points on a
// diagonal the L-inf bisector dips from both ends to the middle. Convexity means the midpoint
// test finds every such dip; the dip's bottom is found by ternary search and becomes a path
// point, so that the path's linear profile holds the true minimum.
void refine(const Site& owner, const Vec2& u, const Vec2& v, double du, double dv, int depth,
            std::vector<Vec2>& path, std::vector<double>& clearance) {
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
    refine(owner, u, at(t), du, dt, depth - 1, path, clearance);
    refine(owner, at(t), v, dt, dv, depth - 1, path, clearance);
    return;
  }
  path.push_back(v);
  clearance.push_back(dv);
}

// Orders one owner pair's pieces into paths: start at an end of odd degree, walk while a
// continuation exists, repeat until every piece is used.
void chain(const Diagram& d, const std::vector<std::int32_t>& ids, std::vector<Stretch>& out) {
  std::unordered_map<Key, std::vector<std::int32_t>, KeyHash> at;
  std::vector<std::int32_t> real;
  for (std::int32_t i : ids) {
    const Piece& p = d.pieces[i];
    if (key_of(p.p) == key_of(p.q)) continue;
    real.push_back(i);
    at[key_of(p.p)].push_back(i);
    at[key_of(p.q)].push_back(i);
  }
  const Piece& first = d.pieces[ids.front()];
  if (real.empty()) {  // only degenerate pieces: one point
    Stretch s;
    s.a = std::min(first.a, first.b);
    s.b = std::max(first.a, first.b);
    s.kind = first.kind;
    s.path = {first.p};
    s.clearance = {first.d1};
    out.push_back(std::move(s));
    return;
  }
  std::set<std::int32_t> unused(real.begin(), real.end());
  while (!unused.empty()) {
    // Prefer a start of odd degree so that an open chain is walked from one end.
    std::int32_t start = *unused.begin();
    Key from = key_of(d.pieces[start].p);
    for (std::int32_t i : unused) {
      const Piece& p = d.pieces[i];
      bool found = false;
      for (const Key& k : {key_of(p.p), key_of(p.q)}) {
        std::size_t n = 0;
        for (std::int32_t j : at[k]) n += unused.count(j);
        if (n % 2 == 1) {
          start = i;
          from = k;
          found = true;
          break;
        }
      }
      if (found) break;
    }
    Stretch s;
    s.a = std::min(first.a, first.b);
    s.b = std::max(first.a, first.b);
    s.kind = d.pieces[start].kind;
    std::int32_t cur = start;
    while (cur >= 0) {
      unused.erase(cur);
      const Piece& p = d.pieces[cur];
      const bool forward = key_of(p.p) == from;
      const Vec2 u = forward ? p.p : p.q, v = forward ? p.q : p.p;
      const double du = forward ? p.d1 : p.d2, dv = forward ? p.d2 : p.d1;
      if (s.path.empty()) {
        s.path.push_back(u);
        s.clearance.push_back(du);
      }
      s.length += dist(u, v);
      refine(d.sites.sites[p.a], u, v, du, dv, 3, s.path, s.clearance);
      from = key_of(v);
      cur = -1;
      for (std::int32_t j : at[from])
        if (unused.count(j)) {
          cur = j;
          break;
        }
    }
    out.push_back(std::move(s));
  }
}

}  // namespace

bool adjacent(const Sites& s, std::int32_t a, std::int32_t b) {
  const Site& x = s.sites[a];
  const Site& y = s.sites[b];
  const std::int32_t fx[3] = {a, x.end0, x.end1};
  const std::int32_t fy[3] = {b, y.end0, y.end1};
  for (std::int32_t i : fx)
    for (std::int32_t j : fy)
      if (i >= 0 && i == j) return true;
  return false;
}

std::vector<Stretch> stretches_of(const Diagram& d) {
  std::map<std::pair<std::int32_t, std::int32_t>, std::vector<std::int32_t>> by_pair;
  for (std::int32_t i = 0; i < std::int32_t(d.pieces.size()); ++i) {
    const Piece& p = d.pieces[i];
    by_pair[{std::min(p.a, p.b), std::max(p.a, p.b)}].push_back(i);
  }
  std::vector<Stretch> out;
  for (auto& [pair, ids] : by_pair) chain(d, ids, out);

  // Vertices where three or more sites meet: pairs without a chain get a point stretch.
  struct Meet {
    Vec2 at;
    double clearance = 0;
    std::vector<std::pair<std::int32_t, PieceKind>> owners;
  };
  std::map<Key, Meet> meets;
  for (const Piece& p : d.pieces)
    for (int end = 0; end < 2; ++end) {
      Meet& m = meets[key_of(end ? p.q : p.p)];
      m.at = end ? p.q : p.p;
      m.clearance = end ? p.d2 : p.d1;
      m.owners.push_back({p.a, p.kind});
      m.owners.push_back({p.b, p.kind});
    }
  for (auto& [k, m] : meets) {
    if (m.clearance <= 0) continue;
    // The pieces around a vertex agree on the side (inside or outside) unless it is on the
    // boundary, where the clearance is zero.
    std::sort(m.owners.begin(), m.owners.end(),
              [](auto& x, auto& y) { return x.first < y.first; });
    m.owners.erase(std::unique(m.owners.begin(), m.owners.end(),
                               [](auto& x, auto& y) { return x.first == y.first; }),
                   m.owners.end());
    if (m.owners.size() < 3) continue;
    PieceKind kind = PieceKind::Adjacent;
    for (auto& o : m.owners)
      if (o.second != PieceKind::Adjacent) kind = o.second;
    if (kind == PieceKind::Adjacent) continue;
    for (std::size_t i = 0; i < m.owners.size(); ++i)
      for (std::size_t j = i + 1; j < m.owners.size(); ++j) {
        const std::int32_t a = m.owners[i].first, b = m.owners[j].first;
        if (by_pair.count({a, b}) || adjacent(d.sites, a, b)) continue;
        Stretch s;
        s.a = a;
        s.b = b;
        s.kind = kind == PieceKind::Internal                                  ? PieceKind::Internal
                 : d.sites.sites[a].shape == d.sites.sites[b].shape ? PieceKind::Notch
                                                                      : PieceKind::External;
        s.path = {m.at};
        s.clearance = {m.clearance};
        out.push_back(std::move(s));
      }
  }
  return out;
}

}  // namespace linf
