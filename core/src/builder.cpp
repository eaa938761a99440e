#include "linf/builder.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "subdivision.hpp"
#include "tiles.hpp"

namespace linf {

namespace {
using namespace detail;

// Joins pieces of the same two owners that continue each other in a straight line.
std::vector<Piece> join_pieces(std::vector<Piece> in) {
  // A total order: workers deliver raw pieces in any order, the result must not depend on it.
  std::sort(in.begin(), in.end(), [](const Piece& x, const Piece& y) {
    return std::tie(x.a, x.b, x.p.x, x.p.y, x.q.x, x.q.y) < std::tie(y.a, y.b, y.p.x, y.p.y, y.q.x, y.q.y);
  });
  std::vector<Piece> out;
  out.reserve(in.size());
  auto close = [](const Vec2& p, const Vec2& q) {
    return std::fabs(p.x - q.x) <= 1e-7 * (1 + std::fabs(p.x)) && std::fabs(p.y - q.y) <= 1e-7 * (1 + std::fabs(p.y));
  };
  auto collinear = [](const Piece& x, const Piece& y) {
    const double ux = x.q.x - x.p.x, uy = x.q.y - x.p.y, vx = y.q.x - y.p.x, vy = y.q.y - y.p.y;
    return std::fabs(ux * vy - uy * vx) <= 1e-9 * std::hypot(ux, uy) * std::hypot(vx, vy);
  };
  for (std::size_t g0 = 0; g0 < in.size();) {
    std::size_t g1 = g0;
    while (g1 < in.size() && in[g1].a == in[g0].a && in[g1].b == in[g0].b) ++g1;
    std::vector<char> used(g1 - g0, 0);
    for (std::size_t i = g0; i < g1; ++i) {
      if (used[i - g0]) continue;
      used[i - g0] = 1;
      Piece cur = in[i];
      for (bool grown = true; grown;) {
        grown = false;
        for (std::size_t j = g0; j < g1; ++j) {
          if (used[j - g0] || !collinear(cur, in[j])) continue;
          Piece o = in[j];
          if (close(cur.q, o.q) || close(cur.p, o.p)) std::swap(o.p, o.q), std::swap(o.d1, o.d2);
          if (close(cur.q, o.p)) { cur.q = o.q; cur.d2 = o.d2; }
          else if (close(cur.p, o.q)) { cur.p = o.p; cur.d1 = o.d1; }
          else continue;
          used[j - g0] = 1;
          grown = true;
        }
      }
      out.push_back(cur);
    }
    g0 = g1;
  }
  return out;
}


// One pass of the subdivision over `root` with the sites `ids`, skipping boxes inside `hole`
// and the parts of pieces there: the far field, or everything in one pass. The top levels,
// breadth first, become the workers' tasks.
std::vector<Piece> run(const std::vector<Site>& sites, std::vector<int> ids, const Box& root, const Box* hole,
                       const BuildOptions& opt, double tau, BuildStats& st) {
  const Model model(sites, std::move(ids), opt, tau);
  std::vector<int> all(model.S.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = int(i);
  std::vector<std::pair<Box, std::vector<int>>> tasks, next;
  tasks.emplace_back(root, std::move(all));
  const Builder top(model, root, hole);
  for (int level = 0; level < 3; ++level) {
    next.clear();
    for (auto& [b, c] : tasks) {
      for (const Box& q : quarters(b)) {
        if (hole && q.x1 >= hole->x1 && q.x2 <= hole->x2 && q.y1 >= hole->y1 && q.y2 <= hole->y2) continue;
        std::vector<int> keep = top.candidates(q, c);
        if (keep.size() > 1) next.emplace_back(q, std::move(keep));
      }
    }
    tasks.swap(next);
  }
  std::vector<Builder> workers(worker_count(tasks.size(), opt.threads), Builder(model, root, hole));
  parallel_for(tasks.size(), opt.threads,
               [&](unsigned w, std::size_t i) { workers[w].process(tasks[i].first, tasks[i].second); });
  std::vector<Piece> raw;
  collect(model, workers, raw, st);
  return raw;
}

// Rounding allowance of the pruning decisions, from the coordinate scale: one value for the
// whole input, whatever the tiles.
double allowance(const Sites& s, const Box& c) {
  double scale = 1;
  for (const Site& t : s.sites)
    scale = std::max({scale, std::fabs(double(t.a.x)), std::fabs(double(t.a.y)), std::fabs(double(t.b.x)),
                      std::fabs(double(t.b.y))});
  scale = std::max({scale, std::fabs(c.x1), std::fabs(c.x2), std::fabs(c.y1), std::fabs(c.y2)});
  return 1e-12 * scale;
}

}  // namespace

std::vector<Piece> build_pieces(const Sites& sites, const Box& clip, const BuildOptions& opt, BuildStats* stats) {
  if (sites.sites.size() < 2) return {};
  const double tau = allowance(sites, clip);
  std::vector<int> all(sites.sites.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = int(i);
  BuildStats st;
  // Two passes. Beyond the sites' bounding box lies the far field, where large groups of
  // sites tie in L-inf and boxes stay crowded (most of the work in one pass over the clip box).
  // Only sites that own a point of the inner box's border can own a point outside it: the
  // segment from such a point to its nearest site point crosses the border inside the same
  // region. So the inner box is built with every site, the far field with those owners only.
  // The margin is off the integer and half-integer grid, so that no piece runs along the
  // inner box's border, and dyadic (5/16), so that halving boxes stays exact.
  double x1 = INFINITY, y1 = INFINITY, x2 = -INFINITY, y2 = -INFINITY;
  for (const Site& t : sites.sites) {
    x1 = std::min({x1, double(t.a.x), double(t.b.x)}), x2 = std::max({x2, double(t.a.x), double(t.b.x)});
    y1 = std::min({y1, double(t.a.y), double(t.b.y)}), y2 = std::max({y2, double(t.a.y), double(t.b.y)});
  }
  const double margin = std::floor(std::max({x2 - x1, y2 - y1, 64.0}) / 64) + 0.3125;
  const Box inner{x1 - margin, y1 - margin, x2 + margin, y2 + margin};
  std::vector<Piece> raw;
  if (!opt.far_field_pass || inner.x1 <= clip.x1 || inner.y1 <= clip.y1 || inner.x2 >= clip.x2 ||
      inner.y2 >= clip.y2) {
    raw = run(sites.sites, all, clip, nullptr, opt, tau, st);
  } else {
    raw = build_tiled(sites.sites, inner, opt, tau, st);
    std::vector<int> border;
    const double eps = 1e-9 * std::max({1.0, std::fabs(inner.x1), std::fabs(inner.x2), std::fabs(inner.y1),
                                        std::fabs(inner.y2)});
    auto on_border = [&](const Vec2& v) {
      return std::fabs(v.x - inner.x1) <= eps || std::fabs(v.x - inner.x2) <= eps || std::fabs(v.y - inner.y1) <= eps ||
             std::fabs(v.y - inner.y2) <= eps;
    };
    for (const Piece& p : raw)
      if (on_border(p.p) || on_border(p.q)) border.push_back(p.a), border.push_back(p.b);
    std::sort(border.begin(), border.end());
    border.erase(std::unique(border.begin(), border.end()), border.end());
    if (border.size() < 2) border = all;  // one site owns the whole border: let the pass decide
    std::vector<Piece> far = run(sites.sites, std::move(border), clip, &inner, opt, tau, st);
    raw.insert(raw.end(), far.begin(), far.end());
  }
  st.raw_pieces = raw.size();
  if (stats) *stats = st;
  return join_pieces(std::move(raw));
}

}  // namespace linf
