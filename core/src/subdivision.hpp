// The box subdivision behind the builder (builder.hpp): a box keeps the sites that can own
// a point of it, and is quartered until few remain; then it is solved directly in convex
// cells where every distance function is affine. Internal to the builder; one Model per
// tile of sites, one Builder per worker thread.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>
#include <vector>

#include <boost/container/small_vector.hpp>

#include "affine.hpp"
#include "cell.hpp"
#include "linf/builder.hpp"

// Internal linkage: each including file (builder.cpp, tiles.cpp) gets its own copy, which the
// compiler inlines as freely as a file-local class (external linkage measured 7% slower).
namespace linf::detail {
namespace {

Affine minus(const Affine& p, const Affine& q) { return {p.a - q.a, p.b - q.b, p.c - q.c}; }

// The largest value of a convex function over a box is at a corner.
double max_over(const DistFn& f, const Box& b) {
  return std::max({f.at(b.x1, b.y1), f.at(b.x2, b.y1), f.at(b.x2, b.y2), f.at(b.x1, b.y2)});
}

// The four quarters of a box, the subdivision step.
std::array<Box, 4> quarters(const Box& b) {
  const double mx = 0.5 * (b.x1 + b.x2), my = 0.5 * (b.y1 + b.y2);
  return {Box{b.x1, b.y1, mx, my}, Box{mx, b.y1, b.x2, my}, Box{b.x1, my, mx, b.y2}, Box{mx, my, b.x2, b.y2}};
}

// Liang-Barsky: the parameter interval [t0, t1] of the segment p + t (q - p), t in [0, 1],
// inside the closed box; false if the segment misses it.
bool clip_to_box(double px, double py, double qx, double qy, const Box& b, double& t0, double& t1) {
  t0 = 0, t1 = 1;
  const double dx = qx - px, dy = qy - py;
  auto edge = [&](double p, double q) {
    if (p == 0) return q >= 0;
    const double r = q / p;
    if (p < 0) { if (r > t1) return false; t0 = std::max(t0, r); }
    else { if (r < t0) return false; t1 = std::min(t1, r); }
    return true;
  };
  return edge(-dx, px - b.x1) && edge(dx, b.x2 - px) && edge(-dy, py - b.y1) && edge(dy, b.y2 - py);
}

// L-inf distance between a closed box and a site: zero if they meet, else attained at a vertex
// of one of them (both are convex polygons and the unit ball is a polygon).
// The same holds for L1, whose breakpoints along a segment are only the axis crossings.
double box_distance(const Box& b, const Site& s, bool l1 = false) {
  if (s.a.x == s.b.x || s.a.y == s.b.y) {  // a point or an axis-parallel edge: a box itself
    const double gx = std::max({b.x1 - double(std::max(s.a.x, s.b.x)), double(std::min(s.a.x, s.b.x)) - b.x2, 0.0});
    const double gy = std::max({b.y1 - double(std::max(s.a.y, s.b.y)), double(std::min(s.a.y, s.b.y)) - b.y2, 0.0});
    return l1 ? gx + gy : std::max(gx, gy);
  }
  auto point_to_box = [&](double x, double y) {
    const double ex = std::max({b.x1 - x, x - b.x2, 0.0}), ey = std::max({b.y1 - y, y - b.y2, 0.0});
    return l1 ? ex + ey : std::max(ex, ey);
  };
  const double ax = double(s.a.x), ay = double(s.a.y), bx = double(s.b.x), by = double(s.b.y);
  double d = std::min(point_to_box(ax, ay), point_to_box(bx, by));
  if (s.is_point() || d == 0) return d;
  double t0, t1;
  if (clip_to_box(ax, ay, bx, by, b, t0, t1)) return 0;
  const double dx = bx - ax, dy = by - ay;
  auto point_to_seg = [&](double x, double y) {
    const double ux = x - ax, uy = y - ay;
    auto f = [&](double t) {
      t = std::clamp(t, 0.0, 1.0);
      const double ex = std::fabs(ux - t * dx), ey = std::fabs(uy - t * dy);
      return l1 ? ex + ey : std::max(ex, ey);
    };
    double m = std::min(f(0), f(1));
    if (dx != 0) m = std::min(m, f(ux / dx));
    if (dy != 0) m = std::min(m, f(uy / dy));
    if (l1) return m;
    if (dx != dy) m = std::min(m, f((ux - uy) / (dx - dy)));
    if (dx != -dy) m = std::min(m, f((ux + uy) / (dx + dy)));
    return m;
  };
  d = std::min({d, point_to_seg(b.x1, b.y1), point_to_seg(b.x2, b.y1), point_to_seg(b.x2, b.y2),
                point_to_seg(b.x1, b.y2)});
  return d;
}

struct LocalCell {
  Cell cell;
  // Active piece of f / g per local site, -1 unknown, kAbsent where the site is above another
  // everywhere on the cell; inline for the usual few sites.
  boost::container::small_vector<signed char, 16> af, ag;
  int ref = -1;  // a present site with an affine f here, the reference for the dominance test
  // The reference's values and the allowances at the vertices, once per cell and reference
  // (absent_in asks for them once per site); empty until asked.
  mutable boost::container::small_vector<double, 10> ref_at, tol_at;
};
constexpr signed char kAbsent = -2;

// The sites of one tile and their distance functions, shared read-only by the workers.
// Local ids run in the order of the global ids (`global`), so every decision that compares
// site indices (the tie rule) is the same in any tile.
struct Model {
  std::vector<Site> S;
  std::vector<int> global;
  BuildOptions opt;
  std::vector<DistFn> f, g;  // L-inf, and the L1 tie-break
  double tau = 0;            // rounding allowance in pruning decisions, the same in every tile
  Model(const std::vector<Site>& all, std::vector<int> ids, const BuildOptions& o, double tau_)
      : global(std::move(ids)), opt(o), tau(tau_) {
    S.reserve(global.size());
    f.reserve(global.size());
    g.reserve(global.size());
    for (int i : global) {
      const Site& t = all[i];
      S.push_back(t);
      f.push_back(make_distfn(t, Norm::Linf));
      g.push_back(make_distfn(t, Norm::L1));
    }
  }
};

// One worker: boxes in, raw pieces out. Boxes are independent, so workers run side by side.
class Builder {
 public:
  Builder(const Model& m, const Box& root, const Box* hole)
      : S_(m.S), clip_(root), hole_(hole ? *hole : Box{1, 1, -1, -1}), has_hole_(hole != nullptr), opt_(m.opt),
        f_(m.f), g_(m.g), tau_(m.tau) {}

  // The sites that can own a point of b, from a superset `cand`.
  std::vector<int> candidates(const Box& b, const std::vector<int>& cand) const {
    std::vector<double> upper(cand.size());
    double U = INFINITY;
    for (std::size_t i = 0; i < cand.size(); ++i) U = std::min(U, upper[i] = max_over(f_[cand[i]], b));
    // The reference for the dominance test: least upper bound, then least in L1 among those.
    // (Within U + tau, as the tiles' halos: a tile picks the same reference as the whole layer.)
    int best = -1;
    double Ug = INFINITY;
    for (std::size_t i = 0; i < cand.size(); ++i) {
      if (upper[i] > U + tau_) continue;
      const double m = max_over(g_[cand[i]], b);
      if (m < Ug) Ug = m, best = cand[i];
    }
    std::vector<int> keep;
    keep.reserve(cand.size());
    const Reference ref = reference(b, best);
    for (int t : cand)
      if (box_distance(b, S_[t]) <= U + tau_ && !dominated(ref, t)) keep.push_back(t);
    if (keep.size() > 2) prune_ties(b, keep);
    return keep;
  }

  void process(const Box& b, const std::vector<int>& cand) {
    if (has_hole_ && b.x1 >= hole_.x1 && b.x2 <= hole_.x2 && b.y1 >= hole_.y1 && b.y2 <= hole_.y2) return;
    ++stats.boxes;
    const std::vector<int> keep = candidates(b, cand);
    if (keep.size() <= 1) return;
    const double w = std::max(b.x2 - b.x1, b.y2 - b.y1);
    // Far from the sites whole groups tie in L-inf (a two-dimensional bisector region) and the
    // count never drops; there the functions are affine over the box, so a direct solve is cheap.
    if (int(keep.size()) <= opt_.local_sites || w <= opt_.min_box ||
        (int(keep.size()) <= opt_.affine_sites && bent(b, keep) <= opt_.bent_sites)) {
      solve(b, keep);
      return;
    }
    for (const Box& q : quarters(b)) process(q, keep);
  }

  BuildStats stats;
  std::vector<Piece> out;

 private:
  // The reference u's values at the corners of the grown box, computed once per box.
  struct Reference {
    int u = -1;
    Vec2 c[4];
    double fu[4], gu[4], e[4];
  };
  Reference reference(const Box& b, int u) const {
    Reference r;
    r.u = u;
    if (u < 0) return r;
    const double m = 1e-3 * std::max(b.x2 - b.x1, b.y2 - b.y1) + tau_;
    r.c[0] = {b.x1 - m, b.y1 - m}, r.c[1] = {b.x2 + m, b.y1 - m}, r.c[2] = {b.x2 + m, b.y2 + m}, r.c[3] = {b.x1 - m, b.y2 + m};
    for (int k = 0; k < 4; ++k)
      r.fu[k] = f_[u].at(r.c[k].x, r.c[k].y), r.gu[k] = g_[u].at(r.c[k].x, r.c[k].y), r.e[k] = tol(r.c[k]);
    return r;
  }
  // Does u come before t at every point of the box and just beyond its sides, by the
  // ownership rule (least L-inf, then least L1)? Then t owns nothing there, ties nowhere, and
  // is never the owner across a side, so it is no candidate. The lower-bound test cannot see
  // this where sites are nearly parallel (the left ends of many tracks seen from far left, a
  // row of equal shapes seen from afar: their distances differ by a constant smaller than the
  // box), so without it the boxes would be cut down to that constant.
  // Sufficient test on the box grown by a small margin: some piece p of f_t above f_u (p <= f_t,
  // and p - f_u is concave, so its least value is at a corner); or some piece not below f_u
  // and some piece of g_t above g_u. Allowances: tol() at each corner.
  bool dominated(const Reference& r, int t) const {
    if (r.u < 0 || t == r.u) return false;
    switch (against(f_[t], r.c, 4, r.fu, r.e)) {
      case Side::Above: return true;
      case Side::Below: return false;
      case Side::Neither: break;
    }
    return against(g_[t], r.c, 4, r.gu, r.e) == Side::Above;
  }

  // Where the pieces of fn stand against `ref` at the points, beyond an allowance at each:
  // Above if some piece is above it at every point, Below if every piece is below it at some
  // point. Comparisons only: this runs for every candidate of every box.
  enum class Side { Above, Below, Neither };
  static Side against(const DistFn& fn, const Vec2* pts, std::size_t n, const double* ref,
                      const double* allowance) {
    bool below = true;
    for (int i = 0; i < fn.n; ++i) {
      bool above = true, under = false;
      for (std::size_t k = 0; k < n; ++k) {
        const double d = fn.piece[i].at(pts[k].x, pts[k].y) - ref[k];
        above = above && d > allowance[k];
        under = under || d < -allowance[k];
        if (!above && under) break;
      }
      if (above) return Side::Above;
      below = below && under;
    }
    return below ? Side::Below : Side::Neither;
  }

  // Far from the sites, whole groups share one affine L-inf function over the box (a
  // two-dimensional bisector region) and the count never drops by subdividing. Inside such a
  // group only the L1 tie-break decides, so members that lose on it everywhere in the box
  // are dropped.
  void prune_ties(const Box& b, std::vector<int>& C) const {
    struct Entry { double a, b, c; int t; };
    std::vector<Entry> flat;
    std::vector<int> rest;
    for (int t : C) {
      const int j = affine_piece(f_[t], b);
      if (j < 0) { rest.push_back(t); continue; }
      const Affine& p = f_[t].piece[j];
      flat.push_back({p.a, p.b, p.c, t});
    }
    if (flat.size() < 2) return;
    std::sort(flat.begin(), flat.end(), [](const Entry& x, const Entry& y) {
      return std::tie(x.a, x.b, x.c, x.t) < std::tie(y.a, y.b, y.c, y.t);
    });
    for (std::size_t g0 = 0; g0 < flat.size();) {
      std::size_t g1 = g0 + 1;
      while (g1 < flat.size() && flat[g1].a == flat[g0].a && flat[g1].b == flat[g0].b && flat[g1].c == flat[g0].c) ++g1;
      if (g1 - g0 == 1) { rest.push_back(flat[g0].t); g0 = g1; continue; }
      double U = INFINITY;
      int best = -1;
      for (std::size_t i = g0; i < g1; ++i) {
        const double m = max_over(g_[flat[i].t], b);
        if (m < U) U = m, best = flat[i].t;
      }
      // Members with identical L1 pieces are all kept: they may part just outside the box,
      // and the owner beyond a box side must be among the candidates.
      const Reference ref = reference(b, best);
      for (std::size_t i = g0; i < g1; ++i)
        if (box_distance(b, S_[flat[i].t], true) <= U + tau_ && !dominated(ref, flat[i].t))
          rest.push_back(flat[i].t);
      g0 = g1;
    }
    std::sort(rest.begin(), rest.end());
    C.swap(rest);
  }

  // The piece of f that is the maximum at every corner of the box, or -1.
  static int affine_piece(const DistFn& f, const Box& b) {
    const int j = f.argmax(b.x1, b.y1);
    if (f.argmax(b.x2, b.y1) != j || f.argmax(b.x2, b.y2) != j || f.argmax(b.x1, b.y2) != j) return -1;
    return j;
  }

  // How many sites' distance functions are not affine over the box (argmax differs at corners).
  int bent(const Box& b, const std::vector<int>& C) const {
    int n = 0;
    for (int t : C) n += affine_piece(f_[t], b) < 0;
    return n;
  }

  // Largest value of an affine piece over a cell: at a vertex.
  static double max_at_vertices(const Affine& a, const Cell& c) {
    double m = -INFINITY;
    for (const Vec2& v : c.v) m = std::max(m, a.at(v.x, v.y));
    return m;
  }

  // Is some piece of f_t above the reference's affine piece everywhere on the closed cell?
  // Then t owns nothing there, ties nowhere, and need not cut the cell (see dominated()).
  bool absent_in(const LocalCell& lc, const std::vector<int>& C, std::size_t t) const {
    if (lc.ref < 0) return false;
    const auto& v = lc.cell.v;
    if (lc.ref_at.empty()) {
      const Affine& q = f_[C[lc.ref]].piece[lc.af[lc.ref]];
      lc.ref_at.resize(v.size()), lc.tol_at.resize(v.size());
      for (std::size_t k = 0; k < v.size(); ++k) lc.ref_at[k] = q.at(v[k].x, v[k].y), lc.tol_at[k] = tol(v[k]);
    }
    return against(f_[C[t]], v.data(), v.size(), lc.ref_at.data(), lc.tol_at.data()) == Side::Above;
  }

  // The reference of a cell after site k became affine on it: whichever of the two has the
  // lower maximum over the cell.
  void update_ref(LocalCell& lc, const std::vector<int>& C, std::size_t k) const {
    if (lc.ref < 0) {
      lc.ref = int(k);
      lc.ref_at.clear();
      return;
    }
    const double mk = max_at_vertices(f_[C[k]].piece[lc.af[k]], lc.cell);
    const double mr = max_at_vertices(f_[C[lc.ref]].piece[lc.af[lc.ref]], lc.cell);
    if (mk < mr) lc.ref = int(k), lc.ref_at.clear();
  }

  // Is piece j of fn below another piece at every vertex of the cell, beyond rounding? Both are
  // affine, so it is below it on the whole cell: j is nowhere the maximum, and clipping the
  // cell down to where it is would only find that out, one copy of the cell at a time.
  static bool never_highest(const DistFn& fn, int j, const Cell& c) {
    for (int i = 0; i < fn.n; ++i) {
      if (i == j) continue;
      const Affine h = minus(fn.piece[j], fn.piece[i]);
      bool below = true;
      for (const Vec2& p : c.v)
        if (!(h.at(p.x, p.y) < -16 * h.err(p.x, p.y))) { below = false; break; }
      if (below) return true;
    }
    return false;
  }

  // Splits `cells` so that site k (of C) is affine on each: by f, where it is present (dropping
  // it from cells where it is absent), or by g.
  void split_by(std::vector<LocalCell>& cells, const std::vector<int>& C, std::size_t k, bool use_g) const {
    const DistFn& fn = use_g ? g_[C[k]] : f_[C[k]];
    // First the cells where k is absent or affine, in place; most sites split no cell, and then
    // the cells are not moved at all.
    boost::container::small_vector<char, 32> split(cells.size(), 0);
    bool any = false;
    for (std::size_t ci = 0; ci < cells.size(); ++ci) {
      LocalCell& lc = cells[ci];
      auto& act = use_g ? lc.ag : lc.af;
      if (!use_g && absent_in(lc, C, k)) {
        act[k] = kAbsent;
        continue;
      }
      int j = fn.argmax(lc.cell.v[0].x, lc.cell.v[0].y);
      bool affine = true;
      for (const Vec2& p : lc.cell.v) {
        const double top = fn.at(p.x, p.y);
        if (fn.piece[j].at(p.x, p.y) < top - 16 * fn.piece[j].err(p.x, p.y)) { affine = false; break; }
      }
      if (affine) {
        act[k] = static_cast<signed char>(j);
        if (!use_g) update_ref(lc, C, k);
        continue;
      }
      split[ci] = 1;
      any = true;
    }
    if (!any) return;
    std::vector<LocalCell> next;
    next.reserve(cells.size() + 4);
    for (std::size_t ci = 0; ci < cells.size(); ++ci) {
      LocalCell& lc = cells[ci];
      if (!split[ci]) {
        next.push_back(std::move(lc));
        continue;
      }
      for (int jj = 0; jj < fn.n; ++jj) {
        if (never_highest(fn, jj, lc.cell)) continue;
        Cell c = lc.cell;
        for (int i = 0; i < fn.n; ++i)
          if (i != jj && !detail::clip_in_place(c, minus(fn.piece[jj], fn.piece[i]))) break;
        if (c.empty()) continue;
        LocalCell sub{std::move(c), lc.af, lc.ag, lc.ref, {}, {}};
        (use_g ? sub.ag : sub.af)[k] = static_cast<signed char>(jj);
        if (!use_g) update_ref(sub, C, k);
        next.push_back(std::move(sub));
      }
    }
    cells.swap(next);
  }

  void solve(const Box& b, const std::vector<int>& C) {
    const std::size_t k = C.size();
    ++stats.solves;
    stats.solved_sites += k;
    std::vector<LocalCell> cells(1);
    cells[0].cell = detail::box_cell(b);
    cells[0].af.assign(k, -1);
    cells[0].ag.assign(k, -1);
    // Nearest at the centre first: they become the cells' references early, and the far
    // sites then mostly drop out instead of cutting the cells.
    const double cx = 0.5 * (b.x1 + b.x2), cy = 0.5 * (b.y1 + b.y2);
    std::vector<std::pair<double, std::size_t>> order(k);
    for (std::size_t i = 0; i < k; ++i) order[i] = {f_[C[i]].at(cx, cy), i};
    std::sort(order.begin(), order.end());
    for (const auto& oi : order) split_by(cells, C, oi.second, false);
    stats.cells += cells.size();

    for (LocalCell& lc : cells) {
      // Sites whose L-inf pieces coincide here need the L1 tie-break, hence affine L1 pieces.
      boost::container::small_vector<char, 16> tied(k, 0);
      bool any = false;
      for (std::size_t i = 0; i < k; ++i) {
        if (lc.af[i] < 0) continue;
        const Affine& fi = f_[C[i]].piece[lc.af[i]];
        for (std::size_t j = i + 1; j < k; ++j)
          if (lc.af[j] >= 0 && detail::same_affine(fi, f_[C[j]].piece[lc.af[j]])) tied[i] = tied[j] = 1, any = true;
      }
      if (!any) {
        regions(lc, C);
        continue;
      }
      std::vector<LocalCell> sub{lc};
      for (std::size_t i = 0; i < k; ++i)
        if (tied[i]) split_by(sub, C, i, true);
      for (const LocalCell& c : sub) regions(c, C);
    }
  }

  // Does local site i come before j where both are affine as in `lc`? Returns the half-plane
  // (h >= 0 where i wins) or, for a constant decision, sets `always`.
  bool compare(const LocalCell& lc, const std::vector<int>& C, std::size_t i, std::size_t j, Affine& h,
               int& always) const {
    const Affine& fi = f_[C[i]].piece[lc.af[i]];
    const Affine& fj = f_[C[j]].piece[lc.af[j]];
    if (!detail::same_affine(fi, fj)) { h = minus(fj, fi); return true; }
    const Affine& gi = g_[C[i]].piece[lc.ag[i]];
    const Affine& gj = g_[C[j]].piece[lc.ag[j]];
    if (!detail::same_affine(gi, gj)) { h = minus(gj, gi); return true; }
    always = rank_before(C[i], C[j]) ? 1 : 0;
    return false;
  }

  bool rank_before(int a, int b) const {
    const bool pa = S_[a].is_point(), pb = S_[b].is_point();
    if (pa != pb) return pa;
    return a < b;
  }

  void regions(const LocalCell& lc, const std::vector<int>& C) {
    const std::size_t k = C.size();
    // Clip first by the sites nearest at the cell's centre: most regions vanish at once.
    Vec2 c{0, 0};
    for (const Vec2& v : lc.cell.v) c.x += v.x, c.y += v.y;
    c.x /= double(lc.cell.v.size()), c.y /= double(lc.cell.v.size());
    // Every function is affine here, so its range over the cell is spanned by the vertices; a
    // site whose least value is above the least greatest value owns nothing, ties nowhere and
    // clips nothing that the site attaining it does not.
    boost::container::small_vector<double, 16> lo(k, INFINITY);
    double U = INFINITY, e = 0;
    for (const Vec2& v : lc.cell.v) e = std::max(e, tol(v));
    for (std::size_t j = 0; j < k; ++j) {
      if (lc.af[j] < 0) continue;
      const Affine& a = f_[C[j]].piece[lc.af[j]];
      double hi = -INFINITY;
      for (const Vec2& v : lc.cell.v) {
        const double x = a.at(v.x, v.y);
        lo[j] = std::min(lo[j], x), hi = std::max(hi, x);
      }
      U = std::min(U, hi);
    }
    boost::container::small_vector<std::pair<double, std::size_t>, 16> order;
    for (std::size_t j = 0; j < k; ++j)
      if (lc.af[j] >= 0 && lo[j] <= U + e) order.push_back({f_[C[j]].piece[lc.af[j]].at(c.x, c.y), j});
    std::sort(order.begin(), order.end());
    // One contender: its greatest value is below every other site's least one by the
    // allowance, so the cell is its region whole, with no tie on any edge: nothing to emit.
    if (order.size() == 1) return;
    for (const auto& oi : order) {
      const std::size_t i = oi.second;
      Cell r = lc.cell;
      for (const auto& oj : order) {
        const std::size_t j = oj.second;
        if (j == i) continue;
        Affine h;
        int always = -1;
        if (compare(lc, C, i, j, h, always)) {
          if (!detail::clip_in_place(r, h)) break;
        } else if (!always) {
          r = Cell{};
          break;
        }
      }
      if (r.empty()) continue;
      emit(r, lc, i, C, order);
    }
  }

  // Restriction of an affine piece to the edge p + s (q - p): value at s = 0 and slope.
  struct Line { double v, d; };
  static Line along(const Affine& a, const Vec2& p, const Vec2& q) {
    const double v = a.at(p.x, p.y);
    return {v, a.at(q.x, q.y) - v};
  }
  // A distance function restricted to an edge: a convex piecewise-linear function of s on
  // [0, 1], kept as its breakpoints and the line active after each.
  struct Profile {
    boost::container::small_vector<double, 6> at;  // at[0] = 0 < at[1] < ... < 1
    boost::container::small_vector<Line, 6> line;
  };
  static Profile profile(const DistFn& f, const Vec2& p, const Vec2& q) {
    Line L[6];
    for (int i = 0; i < f.n; ++i) L[i] = along(f.piece[i], p, q);
    Profile pr;
    double s = 0;
    int cur = 0;
    for (int i = 1; i < f.n; ++i) {  // highest at 0, the steepest among ties
      const double vi = L[i].v, vc = L[cur].v;
      if (vi > vc || (vi == vc && L[i].d > L[cur].d)) cur = i;
    }
    for (;;) {
      pr.at.push_back(s), pr.line.push_back(L[cur]);
      int nxt = -1;
      double ns = 1;
      for (int i = 0; i < f.n; ++i) {  // the first steeper line to overtake
        if (L[i].d <= L[cur].d) continue;
        const double x = (L[cur].v - L[i].v) / (L[i].d - L[cur].d);
        if (x > s + 1e-12 && x < ns) ns = x, nxt = i;
      }
      if (nxt < 0 || ns >= 1 - 1e-12) break;
      s = ns, cur = nxt;
    }
    return pr;
  }
  static std::size_t line_after(const Profile& P, double s) {
    std::size_t i = 0;
    while (i + 1 < P.at.size() && P.at[i + 1] <= s) ++i;
    return i;
  }
  static double value(const Profile& P, double s) {
    const Line& l = P.line[line_after(P, s)];
    return l.v + l.d * s;
  }
  static double eps(double v) { return 1e-11 * (1 + std::fabs(v)); }

  // The first parameter in (s, 1) where B drops below A, or 1.
  static double first_below(const Profile& A, const Profile& B, double s) {
    std::size_t ia = line_after(A, s), ib = line_after(B, s);
    double lo = s;
    for (;;) {
      const double na = ia + 1 < A.at.size() ? A.at[ia + 1] : 1, nb = ib + 1 < B.at.size() ? B.at[ib + 1] : 1;
      const double hi = std::min(na, nb);
      const Line &a = A.line[ia], &b = B.line[ib];
      const double dlo = (b.v + b.d * lo) - (a.v + a.d * lo), dhi = (b.v + b.d * hi) - (a.v + a.d * hi);
      if (dhi < -eps(a.v + a.d * hi)) {
        const double x = dlo <= 0 ? lo : lo + dlo / (dlo - dhi) * (hi - lo);
        return std::max(x, std::nextafter(s, 2.0));
      }
      if (hi >= 1) return 1;
      lo = hi;
      if (na <= hi) ++ia;
      if (nb <= hi) ++ib;
    }
  }

  // Interior parameters where the owner beyond the edge can change: where the lower envelope
  // of the profiles (least L1) changes hands, and every profile's breakpoints (the slopes
  // across may change there). Walking the envelope costs its size times the profiles, where
  // all pairwise crossings cost the square of the profiles: far from a row of equal shapes
  // dozens of sites tie along one edge.
  template <class Profiles, class Cuts>
  static void envelope_cuts(const Profiles& P, Cuts& out) {
    for (const Profile& pr : P) out.insert(out.end(), pr.at.begin() + 1, pr.at.end());
    auto lowest_after = [&](double s) {
      std::size_t best = 0;
      double bv = value(P[0], s), bd = P[0].line[line_after(P[0], s)].d;
      for (std::size_t i = 1; i < P.size(); ++i) {
        const double v = value(P[i], s), d = P[i].line[line_after(P[i], s)].d;
        if (v < bv - eps(bv) || (v <= bv + eps(bv) && d < bd)) best = i, bv = v, bd = d;
      }
      return best;
    };
    double s = 0;
    std::size_t cur = lowest_after(s);
    for (int guard = 0; guard < 4 * int(P.size()) + 16; ++guard) {
      double next = 1;
      for (std::size_t i = 0; i < P.size(); ++i)
        if (i != cur) next = std::min(next, first_below(P[cur], P[i], s));
      if (next >= 1 - 1e-12) return;
      out.push_back(next);
      s = next;
      cur = lowest_after(s);
    }
  }

  // `contenders`: the cell's sites that can be least somewhere on it (see regions()); no other
  // site ties with t on t's region, where t is at most the least greatest value.
  template <class Contenders>
  void emit(const Cell& r, const LocalCell& lc, std::size_t ti, const std::vector<int>& C,
            const Contenders& contenders) {
    const int t = C[ti];
    const std::size_t n = r.v.size();
    // Every contender's value and the allowance at every vertex, once: each vertex is the end
    // of two edges, and the tie test below reads them for every contender.
    const std::size_t k = contenders.size();
    boost::container::small_vector<double, 160> val(n * k);
    boost::container::small_vector<double, 10> tl(n);
    std::size_t tk = 0;  // t's place among the contenders
    for (std::size_t j = 0; j < k; ++j)
      if (contenders[j].second == ti) tk = j;
    for (std::size_t v = 0; v < n; ++v) {
      tl[v] = tol(r.v[v]);
      for (std::size_t j = 0; j < k; ++j) {
        const std::size_t cj = contenders[j].second;
        val[v * k + j] = f_[C[cj]].piece[lc.af[cj]].at(r.v[v].x, r.v[v].y);
      }
    }
    for (std::size_t e = 0; e < n; ++e) {
      const Vec2 p = r.v[e], q = r.v[(e + 1) % n];
      if ((q.x - p.x) * (q.x - p.x) + (q.y - p.y) * (q.y - p.y) <= 1e-18) continue;  // shorter than 1e-9
      const Vec2 nrm{q.y - p.y, p.x - q.x};
      const Vec2 m{0.5 * (p.x + q.x), 0.5 * (p.y + q.y)};
      if ((nrm.x < 0 && m.x <= clip_.x1) || (nrm.x > 0 && m.x >= clip_.x2) || (nrm.y < 0 && m.y <= clip_.y1) ||
          (nrm.y > 0 && m.y >= clip_.y2))
        continue;
      // The neighbour is found from this side, not from the clip that made the edge: where several
      // sites tie in L-inf their bisector lines coincide, and the owner beyond can change
      // along the edge where the L1 tie-break changes, that is at crossings of the tied
      // sites' L1 profiles.
      // Within the cell every L-inf function is affine, so a site ties with t along the whole
      // edge iff it does at both ends, and no L-inf piece changes along the edge's interior.
      // The cell is closed, so the active pieces give every function's value at its vertices.
      const std::size_t e2 = (e + 1) % n;
      const double* vp = &val[e * k];
      const double* vq = &val[e2 * k];
      boost::container::small_vector<int, 8> tied{t};
      for (std::size_t j = 0; j < k; ++j) {
        if (j == tk) continue;
        if (std::fabs(vp[j] - vp[tk]) <= tl[e] && std::fabs(vq[j] - vq[tk]) <= tl[e2])
          tied.push_back(C[contenders[j].second]);
      }
      std::sort(tied.begin() + 1, tied.end());  // the sites' order, as C's: near-ties decide alike
      if (tied.size() == 1) continue;  // a split inside t's own region
      // The owner beyond is one of the tied; emit_piece keeps only t < owner (the other side
      // reports the rest), so where all come before t there is nothing to emit.
      if (*std::max_element(tied.begin() + 1, tied.end()) < t) continue;
      // Only sites that also share the least slope across the edge go to the L1 tie-break.
      const double len = std::hypot(nrm.x, nrm.y);
      const Vec2 un{nrm.x / len, nrm.y / len};
      boost::container::small_vector<double, 8> sl(tied.size());
      double smin = INFINITY;
      for (std::size_t i = 0; i < tied.size(); ++i)
        smin = std::min(smin, sl[i] = slope(f_[tied[i]], m, un, f_[tied[i]].at(m.x, m.y), tol(m)));
      std::size_t least = 0;
      for (std::size_t i = 0; i < tied.size(); ++i) least += sl[i] <= smin + 1e-12;
      boost::container::small_vector<double, 16> cuts{0.0, 1.0};
      if (least > 1) {  // with one site alone at the least slope there is no L1 envelope to walk
        boost::container::small_vector<Profile, 4> g;
        for (std::size_t i = 0; i < tied.size(); ++i)
          if (sl[i] <= smin + 1e-12) g.push_back(profile(g_[tied[i]], p, q));
        envelope_cuts(g, cuts);
      }
      std::sort(cuts.begin(), cuts.end());
      // Neighbouring parts with the same owner beyond go out as one piece.
      auto at = [&](double s) { return Vec2{p.x + s * (q.x - p.x), p.y + s * (q.y - p.y)}; };
      double from = 0;
      int owner = -1;
      for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
        if (cuts[i + 1] - cuts[i] <= 1e-9) continue;
        const Vec2 a = at(cuts[i]), b = at(cuts[i + 1]);
        const int u = owner_beyond({0.5 * (a.x + b.x), 0.5 * (a.y + b.y)}, nrm, tied);
        if (u != owner) {
          if (owner >= 0) emit_piece(at(from), a, t, owner);
          from = cuts[i], owner = u;
        }
      }
      if (owner >= 0) emit_piece(at(from), q, t, owner);
    }
  }

  void emit_piece(const Vec2& p, const Vec2& q, int t, int u) {
    if (u == t || t > u) return;  // no edge, or the other side reports it
    const double dp = f_[t].at(p.x, p.y), dq = f_[t].at(q.x, q.y);
    if (std::fabs(dp - f_[u].at(p.x, p.y)) > tol(p) || std::fabs(dq - f_[u].at(q.x, q.y)) > tol(q)) return;
    double t0, t1;  // the far-field pass keeps only what lies outside the inner box
    if (has_hole_ && clip_to_box(p.x, p.y, q.x, q.y, hole_, t0, t1) && t1 > t0) {
      const double dx = q.x - p.x, dy = q.y - p.y;
      const Vec2 a{p.x + t0 * dx, p.y + t0 * dy}, b{p.x + t1 * dx, p.y + t1 * dy};
      if (t0 > 1e-12) add_piece(p, a, t, u, dp, f_[t].at(a.x, a.y));
      if (t1 < 1 - 1e-12) add_piece(b, q, t, u, f_[t].at(b.x, b.y), dq);
      return;
    }
    add_piece(p, q, t, u, dp, dq);
  }

  // d1, d2: the clearance at p and q.
  void add_piece(const Vec2& p, const Vec2& q, int t, int u, double d1, double d2) {
    Piece pc;
    pc.p = p, pc.q = q;
    pc.a = t, pc.b = u;
    pc.d1 = d1;
    pc.d2 = d2;
    out.push_back(pc);
  }

  double tol(const Vec2& p) const { return tau_ + 1e-13 * (std::fabs(p.x) + std::fabs(p.y)); }

  static double slope(const DistFn& f, const Vec2& m, const Vec2& d, double value, double tol) {
    double s = -INFINITY;
    for (int i = 0; i < f.n; ++i)
      if (f.piece[i].at(m.x, m.y) >= value - tol) s = std::max(s, f.piece[i].a * d.x + f.piece[i].b * d.y);
    return s;
  }

  // The owner just beyond m in direction d: compare distance, its slope along d, then the
  // L1 tie-break with its slope, then rank.
  // Only sites tied with the edge's own site along the whole edge can own beyond it: every
  // other site is above it at an end, so it is not least at the edge's points.
  template <class Sites>
  int owner_beyond(const Vec2& m, const Vec2& d, const Sites& C) const {
    const double len = std::hypot(d.x, d.y);
    const Vec2 u{d.x / len, d.y / len};
    const double tl = tol(m);
    double fmin = INFINITY;
    for (int t : C) fmin = std::min(fmin, f_[t].at(m.x, m.y));
    // The L1 value and slope only where the L-inf slopes tie (computed at most once a site).
    struct Candidate {
      int t = -1;
      double s = 0, gv = 0, gs = 0;
      bool has_g = false;
    };
    auto with_g = [&](Candidate& c) {
      if (!c.has_g) c.gv = g_[c.t].at(m.x, m.y), c.gs = slope(g_[c.t], m, u, c.gv, tl), c.has_g = true;
    };
    Candidate best;
    for (int t : C) {
      const double fv = f_[t].at(m.x, m.y);
      if (fv > fmin + tl) continue;
      Candidate c;
      c.t = t;
      c.s = slope(f_[t], m, u, fv, tl);
      bool better;
      if (best.t < 0) better = true;
      else if (std::fabs(c.s - best.s) > 1e-12) better = c.s < best.s;
      else {
        with_g(c), with_g(best);
        if (std::fabs(c.gv - best.gv) > tl) better = c.gv < best.gv;
        else if (std::fabs(c.gs - best.gs) > 1e-12) better = c.gs < best.gs;
        else better = rank_before(t, best.t);
      }
      if (better) best = c;
    }
    return best.t;
  }


  const std::vector<Site>& S_;
  const Box clip_;
  const Box hole_;
  const bool has_hole_;
  const BuildOptions opt_;
  const std::vector<DistFn>& f_;
  const std::vector<DistFn>& g_;
  const double tau_;
};

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


// The workers' pieces, with global site ids, joined (about a third of the raw pieces remain),
// into `raw` (its capacity kept: tile after tile it is the same buffer, not fresh pages); their
// counts added to `st`.
void collect(const Model& m, const std::vector<Builder>& workers, BuildStats& st, std::vector<Piece>& raw) {
  std::size_t n = 0;
  for (const Builder& w : workers) n += w.out.size();
  raw.clear();
  raw.reserve(n);
  for (const Builder& w : workers) {
    for (Piece p : w.out) {
      p.a = m.global[p.a], p.b = m.global[p.b];
      raw.push_back(p);
    }
    st.boxes += w.stats.boxes, st.solves += w.stats.solves, st.solved_sites += w.stats.solved_sites;
    st.cells += w.stats.cells;
  }
  st.raw_pieces += raw.size();
  join_pieces(raw);
}


}  // namespace
}  // namespace linf::detail
