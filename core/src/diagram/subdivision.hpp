// The box subdivision behind the builder (builder.hpp): a box keeps the sites that can own
// a point of it, and is quartered until few remain; then it is solved directly in convex
// cells where every distance function is affine. Internal to the builder; one Model per
// tile of sites (model.hpp: the geometry and the ownership rule it decides by), one Builder
// per worker thread (the algorithm: boxes, cells, regions, pieces).
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>
#include <vector>

#include <boost/container/small_vector.hpp>

#include "affine.hpp"
#include "bounds.hpp"
#include "convex_cell.hpp"
#include "envelope.hpp"
#include "join.hpp"
#include "linf/diagram/builder.hpp"
#include "model.hpp"

// Internal linkage: each including file (builder.cpp, tiles.cpp) gets its own copy, which the
// compiler inlines as freely as a file-local class (external linkage measured 7% slower).
namespace linf::detail {
namespace {

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

// One worker: boxes in, raw pieces out. Boxes are independent, so workers run side by side.
class Builder {
 public:
  Builder(const Model& m, const Box& root, const Box* hole)
      : m_(m), S_(m.S), clip_(root), hole_(hole ? *hole : Box{1, 1, -1, -1}), has_hole_(hole != nullptr), opt_(m.opt),
        f_(m.f), g_(m.g), tau_(m.tau) {}

  // The sites that can own a point of b, from a superset `cand`.
  std::vector<int> candidates(const Box& b, const std::vector<int>& cand) const {
    std::vector<double> upper(cand.size());
    double U = INFINITY;
    for (std::size_t i = 0; i < cand.size(); ++i) U = std::min(U, upper[i] = max_over(f_[cand[i]], S_[cand[i]], b, false));
    // The reference for the dominance test: least upper bound, then least in L1 among those.
    // (Within U + tau, as the tiles' halos: a tile picks the same reference as the whole layer.)
    int best = -1;
    double Ug = INFINITY;
    for (std::size_t i = 0; i < cand.size(); ++i) {
      if (upper[i] > U + tau_) continue;
      const double m = max_over(g_[cand[i]], S_[cand[i]], b, true);
      if (m < Ug) Ug = m, best = cand[i];
    }
    std::vector<int> keep;
    keep.reserve(cand.size());
    const Model::Reference ref = m_.reference(b, best);
    for (int t : cand) {
      // A site that meets the box is at distance 0 there: no other site comes before it there
      // (Model::dominated could only say no).
      const double lower = box_distance(b, S_[t]);
      if (lower <= U + tau_ && (lower == 0 || !m_.dominated(ref, t))) keep.push_back(t);
    }
    if (keep.size() > 2) prune_ties(b, keep);
    return keep;
  }

  // A site that the one reference does not dominate may still be dominated by another
  // candidate: one of a row's far line ends, seen past its near ones; a corner behind a near
  // edge. Half the sites of the SRAM's local solves owned nothing in them. So in small solves
  // every candidate is tried as the reference, first by the ownership rule at the box's
  // centre, which a dominating site must pass. Dominance is transitive, so a site dominated by
  // one that goes itself is dominated by what removes that one. Only in the solve: done in
  // candidates() it made the quarters look cheaper than their box to quarter_or_solve(), and a
  // disk of 4,096 vertices took 43% more solves.
  void prune_dominated(const Box& b, std::vector<int>& keep) const {
    const std::size_t n = keep.size();
    const Vec2 c{0.5 * (b.x1 + b.x2), 0.5 * (b.y1 + b.y2)};
    const double e = m_.tol(c);
    boost::container::small_vector<double, 32> fc(n), gc(n);
    for (std::size_t i = 0; i < n; ++i) fc[i] = f_[keep[i]].at(c.x, c.y), gc[i] = g_[keep[i]].at(c.x, c.y);
    boost::container::small_vector<Model::Reference, 32> refs(n);
    std::vector<int> kept;
    kept.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
      bool dominated = false;
      if (box_distance(b, S_[keep[i]]) == 0) {  // it meets the box: see candidates()
        kept.push_back(keep[i]);
        continue;
      }
      for (std::size_t j = 0; j < n && !dominated; ++j) {
        if (j == i || !(fc[i] > fc[j] + e || (fc[i] >= fc[j] - e && gc[i] > gc[j] + e))) continue;
        if (refs[j].u < 0) refs[j] = m_.reference(b, keep[j]);
        dominated = m_.dominated(refs[j], keep[i]);
      }
      if (!dominated) kept.push_back(keep[i]);
    }
    keep.swap(kept);
  }

  void process(const Box& b, const std::vector<int>& cand) {
    if (inside_hole(b)) return;
    ++stats.boxes;
    process_pruned(b, candidates(b, cand));
  }

  BuildStats stats;
  std::vector<Piece> out;

 private:
  bool inside_hole(const Box& b) const {
    return has_hole_ && b.x1 >= hole_.x1 && b.x2 <= hole_.x2 && b.y1 >= hole_.y1 && b.y2 <= hole_.y2;
  }

  // `keep`: the candidates of b.
  void process_pruned(const Box& b, const std::vector<int>& keep) {
    if (keep.size() <= 1) return;
    const double w = std::max(b.x2 - b.x1, b.y2 - b.y1);
    if (int(keep.size()) <= opt_.local_sites || w <= opt_.min_box) {
      solve(b, keep);
      return;
    }
    // Before the direct solve of an affine box: the sites of a group tied in L-inf over the
    // whole box are all contenders everywhere in it, and its solve costs the square of the
    // group, where halves of half the sites cost half as much together (under a row of 25
    // boxes, with three far ones: 2,735 solves, a sixth of them of 25 to 44 sites, took twice
    // as long as 5,092 smaller ones).
    if (halve_across_ties(b, keep)) return;
    // Far from the sites whole groups tie in L-inf (a two-dimensional bisector region) and the
    // count never drops; there the functions are affine over the box, so a direct solve is cheap.
    if (int(keep.size()) <= opt_.affine_sites && bent(b, keep) <= opt_.bent_sites) {
      solve(b, keep);
      return;
    }
    if (int(keep.size()) <= opt_.crowded_sites && curved(keep)) {
      quarter_or_solve(b, keep);
      return;
    }
    // A long box (the tasks of a long layer are as long as the layer) is cut across its length
    // first: a box keeps the sites near any of its points, so a long thin one keeps many more
    // than a square of the same area, and quartering would keep its shape down to the leaves.
    const double wx = b.x2 - b.x1, wy = b.y2 - b.y1;
    if (wx > 1.5 * wy || wy > 1.5 * wx) {
      for (const Box& h : halves(b, wx > wy ? 2 : 1)) process(h, keep);
      return;
    }
    for (const Box& q : quarters(b)) process(q, keep);
  }

  // Halves b across the gradients of a group tied in L-inf (tie_axis), while halving thins
  // the sites out (identical sites never part, and the halves would go on down to nothing).
  bool halve_across_ties(const Box& b, const std::vector<int>& keep) {
    const int axis = tie_axis(b, keep);
    if (!axis) return false;
    const std::array<Box, 2> h = halves(b, axis);
    std::array<std::vector<int>, 2> hk;
    for (int i = 0; i < 2; ++i) {
      if (inside_hole(h[i])) continue;
      hk[i] = candidates(h[i], keep);
      if (4 * hk[i].size() > 3 * keep.size()) return false;
    }
    for (int i = 0; i < 2; ++i) {
      if (inside_hole(h[i])) continue;
      ++stats.boxes;
      process_pruned(h[i], hk[i]);
    }
    return true;
  }

  // Seen from afar, a row of line ends on one line (a cut through a block of tracks, the
  // ends of an array, the top of a row of wires) ties in L-inf over a whole field: every end
  // is at the same L-inf distance, x - x0 say, and only the L1 tie-break, which grows with
  // the distance along the row, tells them apart. Quartering does not thin such a box out
  // along the row's normal, only along the row, so square boxes stay as small as a few
  // tracks out to the end of the field: boxes, and raw pieces, grew with the square of the
  // row's length (7,582 ends on the cut of a five-million-wire block's half had not finished
  // in 45 minutes). Where every site is affine over the box with its gradient along one axis,
  // the box is halved across the other axis only.
  // 1: every gradient along x (halve in y), 2: along y (halve in x), 0: neither.
  int tie_axis(const Box& b, const std::vector<int>& keep) const {
    bool along_x = true, along_y = true;
    for (int t : keep) {
      const int j = Model::affine_piece(f_[t], b);
      if (j < 0) return 0;
      const Affine& p = f_[t].piece[j];
      along_x = along_x && p.b == 0;
      along_y = along_y && p.a == 0;
      if (!along_x && !along_y) return 0;
    }
    return along_x ? 1 : 2;
  }

  // Inside a shape drawn with many edge directions (a disk, a bend) every slanted edge's L-inf
  // distance bends along the lines from its ends in the direction of the square's corner that
  // touches it, and these lines run across the whole shape: the regions are long parallel
  // strips (a disk's run diagonally from the rim to the axes). A quarter then keeps about half
  // of its box's sites, and quartering only multiplies the boxes, down to boxes as narrow as a
  // strip (a 4,096-gon: 1.3 million solves for 6,354 pieces). Where the quarters together
  // would cost about as much as their box (a solve costs about the square of its sites), the
  // box is solved whole. Layouts of axis-parallel and 45-degree edges never come here: their
  // quarters thin out, and the test itself would cost them.
  bool curved(const std::vector<int>& keep) const {
    std::size_t slanted = 0;
    for (int t : keep) {
      const Coord dx = S_[t].b.x - S_[t].a.x, dy = S_[t].b.y - S_[t].a.y;
      slanted += dx != 0 && dy != 0 && dx != dy && dx != -dy;
    }
    return 3 * slanted >= keep.size();
  }
  void quarter_or_solve(const Box& b, const std::vector<int>& keep) {
    const std::array<Box, 4> q = quarters(b);
    std::array<std::vector<int>, 4> qk;
    double work = 0;
    for (int i = 0; i < 4; ++i) {
      if (inside_hole(q[i])) continue;
      qk[i] = candidates(q[i], keep);
      work += double(qk[i].size()) * double(qk[i].size());
    }
    if (work >= 0.75 * double(keep.size()) * double(keep.size())) {
      solve(b, keep);
      return;
    }
    for (int i = 0; i < 4; ++i) {
      if (inside_hole(q[i])) continue;
      ++stats.boxes;
      process_pruned(q[i], qk[i]);
    }
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
      const int j = Model::affine_piece(f_[t], b);
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
        const double m = max_over(g_[flat[i].t], S_[flat[i].t], b, true);
        if (m < U) U = m, best = flat[i].t;
      }
      // Members with identical L1 pieces are all kept: they may part just outside the box,
      // and the owner beyond a box side must be among the candidates.
      const Model::Reference ref = m_.reference(b, best);
      for (std::size_t i = g0; i < g1; ++i)
        if (box_distance(b, S_[flat[i].t], true) <= U + tau_ && !m_.dominated(ref, flat[i].t))
          rest.push_back(flat[i].t);
      g0 = g1;
    }
    std::sort(rest.begin(), rest.end());
    C.swap(rest);
  }

  // How many sites' distance functions are not affine over the box (argmax differs at corners).
  int bent(const Box& b, const std::vector<int>& C) const {
    int n = 0;
    for (int t : C) n += Model::affine_piece(f_[t], b) < 0;
    return n;
  }

  // Largest value of an affine piece over a cell: at a vertex.
  static double max_at_vertices(const Affine& a, const Cell& c) {
    double m = -INFINITY;
    for (const Vec2& v : c.v) m = std::max(m, a.at(v.x, v.y));
    return m;
  }

  // Is some piece of f_t above the reference's affine piece everywhere on the closed cell?
  // Then t owns nothing there, ties nowhere, and need not cut the cell (see Model::dominated()).
  bool absent_in(const LocalCell& lc, const std::vector<int>& C, std::size_t t) const {
    if (lc.ref < 0) return false;
    const auto& v = lc.cell.v;
    if (lc.ref_at.empty()) {
      const Affine& q = f_[C[lc.ref]].piece[lc.af[lc.ref]];
      lc.ref_at.resize(v.size()), lc.tol_at.resize(v.size());
      for (std::size_t k = 0; k < v.size(); ++k) lc.ref_at[k] = q.at(v[k].x, v[k].y), lc.tol_at[k] = m_.tol(v[k]);
    }
    return m_.against(C[t], v.data(), v.size(), lc.ref_at.data(), lc.tol_at.data()) == Model::Side::Above;
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
    // A split cell's first part takes its place, the others go to the end: the cells' order
    // decides nothing, and the cells that are not split are not moved.
    const std::size_t n0 = cells.size();
    for (std::size_t ci = 0; ci < n0; ++ci) {
      if (!split[ci]) continue;
      const Cell whole = std::move(cells[ci].cell);
      const int ref = cells[ci].ref;
      bool placed = false;
      for (int jj = 0; jj < fn.n; ++jj) {
        if (Model::never_highest(fn, jj, whole)) continue;
        Cell c = whole;
        for (int i = 0; i < fn.n; ++i)
          if (i != jj && !detail::clip_in_place(c, minus(fn.piece[jj], fn.piece[i]))) break;
        if (c.empty()) continue;
        if (!placed) {
          LocalCell& lc = cells[ci];
          lc.cell = std::move(c);
          lc.ref_at.clear(), lc.tol_at.clear();
          (use_g ? lc.ag : lc.af)[k] = static_cast<signed char>(jj);
          if (!use_g) update_ref(lc, C, k);
          placed = true;
          continue;
        }
        LocalCell sub{std::move(c), cells[ci].af, cells[ci].ag, ref, {}, {}};
        (use_g ? sub.ag : sub.af)[k] = static_cast<signed char>(jj);
        if (!use_g) update_ref(sub, C, k);
        cells.push_back(std::move(sub));
      }
      if (!placed) cells[ci].cell = Cell{};  // nothing left of it (rounding)
    }
    cells.erase(std::remove_if(cells.begin(), cells.end(), [](const LocalCell& lc) { return lc.cell.empty(); }),
                cells.end());
  }

  void solve(const Box& b, std::vector<int> C) {
    if (C.size() > 2 && int(C.size()) <= opt_.paired_sites) prune_dominated(b, C);
    const std::size_t k = C.size();
    ++stats.solves;
    stats.solved_sites += k;
    stats.solved_pairs += k * k;
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
      // Sites whose L-inf pieces coincide here need the L1 tie-break, hence affine L1 pieces;
      // not two points or axis-parallel edges, whose order is a half-plane or their rank
      // (Model::axis_order). Pairs among the sites present here only: in a large solve most
      // sites are absent from most cells.
      boost::container::small_vector<std::size_t, 16> present;
      for (std::size_t i = 0; i < k; ++i)
        if (lc.af[i] >= 0) present.push_back(i);
      boost::container::small_vector<char, 16> tied(k, 0);
      bool any = false;
      for (std::size_t x = 0; x < present.size(); ++x) {
        const std::size_t i = present[x];
        const Affine& fi = f_[C[i]].piece[lc.af[i]];
        for (std::size_t y = x + 1; y < present.size(); ++y) {
          const std::size_t j = present[y];
          Affine h;
          if (detail::same_affine(fi, f_[C[j]].piece[lc.af[j]]) &&
              m_.axis_order(C[i], C[j], fi, h) == Model::Order::Unknown)
            tied[i] = tied[j] = 1, any = true;
        }
      }
      if (!any) {
        regions(lc, C);
        continue;
      }
      ++stats.tie_cells;
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
    switch (m_.axis_order(C[i], C[j], fi, h)) {
      case Model::Order::HalfPlane: return true;
      case Model::Order::Equal: always = m_.rank_before(C[i], C[j]) ? 1 : 0; return false;
      case Model::Order::Unknown: break;
    }
    const Affine& gi = g_[C[i]].piece[lc.ag[i]];
    const Affine& gj = g_[C[j]].piece[lc.ag[j]];
    if (!detail::same_affine(gi, gj)) { h = minus(gj, gi); return true; }
    always = m_.rank_before(C[i], C[j]) ? 1 : 0;
    return false;
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
    for (const Vec2& v : lc.cell.v) e = std::max(e, m_.tol(v));
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
    // A piece goes out from the region of the lower of its two sites (emit_piece), so the
    // region of the highest contender has nothing to emit: it is not even cut out.
    int top = -1;
    for (const auto& oi : order) top = std::max(top, C[oi.second]);
    for (const auto& oi : order) {
      const std::size_t i = oi.second;
      if (C[i] == top) continue;
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

  // `contenders`: the cell's sites that can be least somewhere on it (see regions()); no other
  // site ties with t on t's region, where t is at most the least greatest value.
  template <class Contenders>
  void emit(const Cell& r, const LocalCell& lc, std::size_t ti, const std::vector<int>& C,
            const Contenders& contenders) {
    const int t = C[ti];
    const std::size_t n = r.v.size();
    // A piece goes out from the side of the lower site (emit_piece), so an edge matters only
    // where a contender above t ties with t along it. Their values and t's, and the allowance,
    // at every vertex once: each vertex is the end of two edges. The contenders below t are
    // asked only on those edges, for the owner beyond.
    boost::container::small_vector<std::size_t, 16> up, down;  // contenders' places above t, below t
    for (std::size_t j = 0; j < contenders.size(); ++j) {
      const std::size_t cj = contenders[j].second;
      if (cj != ti) (C[cj] > t ? up : down).push_back(cj);
    }
    if (up.empty()) return;
    const std::size_t k = up.size() + 1;  // t, then those above it
    auto value = [&](std::size_t cj, const Vec2& v) { return f_[C[cj]].piece[lc.af[cj]].at(v.x, v.y); };
    boost::container::small_vector<double, 160> val(n * k, boost::container::default_init);
    boost::container::small_vector<double, 10> tl(n, boost::container::default_init);
    for (std::size_t v = 0; v < n; ++v) {
      tl[v] = m_.tol(r.v[v]);
      val[v * k] = value(ti, r.v[v]);
      for (std::size_t j = 1; j < k; ++j) val[v * k + j] = value(up[j - 1], r.v[v]);
    }
    for (std::size_t e = 0; e < n; ++e) {
      const std::size_t e2 = e + 1 < n ? e + 1 : 0;
      // Within the cell every L-inf function is affine, so a site ties with t along the whole
      // edge iff it does at both ends, and no L-inf piece changes along the edge's interior.
      // The cell is closed, so the active pieces give every function's value at its vertices.
      // Most edges have no site above t tied along them (t's own region goes on beyond, or a
      // site below t reports it), and are left first.
      const double* vp = &val[e * k];
      const double* vq = &val[e2 * k];
      auto ties = [&](double at_p, double at_q) {  // a site's values at p and q against t's
        return std::fabs(at_p - vp[0]) <= tl[e] && std::fabs(at_q - vq[0]) <= tl[e2];
      };
      std::size_t first_up = 1;
      while (first_up < k && !ties(vp[first_up], vq[first_up])) ++first_up;
      if (first_up == k) continue;
      const Vec2 p = r.v[e], q = r.v[e2];
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
      boost::container::small_vector<int, 8> tied{t};
      for (std::size_t j = first_up; j < k; ++j)
        if (ties(vp[j], vq[j])) tied.push_back(C[up[j - 1]]);
      for (const std::size_t cj : down)
        if (ties(value(cj, p), value(cj, q))) tied.push_back(C[cj]);
      std::sort(tied.begin() + 1, tied.end());  // the sites' order, as C's: near-ties decide alike
      // A region of no width: a slanted edge's slanted piece meets its axis piece along a
      // diagonal where that axis piece ties with other sites over an area (a steep edge with a
      // point at its end's x), and the rounding of the clip leaves t a sliver along that line,
      // where t ties but loses to the sites tied there just inside as well as beyond.
      if (detail::steep_edge(m_.S[t]) && m_.owner_beyond(m, Vec2{-nrm.x, -nrm.y}, tied) != t) continue;
      // Only sites that also share the least slope across the edge go to the L1 tie-break.
      // hypot(x, 0) is |x| (C's Annex F): an axis-parallel edge's length without hypot's cost.
      const double len = nrm.x == 0 ? std::fabs(nrm.y) : nrm.y == 0 ? std::fabs(nrm.x) : std::hypot(nrm.x, nrm.y);
      const Vec2 un{nrm.x / len, nrm.y / len};
      const double tm = m_.tol(m);
      boost::container::small_vector<const Affine*, 8> beyond(tied.size());  // each one's piece beyond m
      boost::container::small_vector<double, 8> sl(tied.size());
      double smin = INFINITY;
      for (std::size_t i = 0; i < tied.size(); ++i) {
        const DistFn& fn = f_[tied[i]];
        beyond[i] = &Model::steepest(fn, m, un, fn.at(m.x, m.y), tm);
        smin = std::min(smin, sl[i] = beyond[i]->a * un.x + beyond[i]->b * un.y);
      }
      std::size_t least = 0, first = 0;  // how many have the least slope, and the first of them
      for (std::size_t i = 0; i < tied.size(); ++i)
        if (sl[i] <= smin + 1e-12 && least++ == 0) first = i;
      // One site alone at the least slope owns beyond the whole edge (Model::owner_beyond's
      // first test): no L1 tie-break to walk, no part to ask about.
      if (least == 1) {
        emit_piece(p, q, t, tied[first]);
        continue;
      }
      boost::container::small_vector<double, 16> cuts{0.0, 1.0};
      boost::container::small_vector<int, 8> G;
      boost::container::small_vector<const Affine*, 8> GP;
      for (std::size_t i = 0; i < tied.size(); ++i)
        if (sl[i] <= smin + 1e-12) G.push_back(tied[i]), GP.push_back(beyond[i]);
      const int across = m_.axis_cuts(G.data(), GP.data(), G.size(), p, q, vp[0], vq[0], tl[e], tl[e2], cuts);
      if (across < 0) {
        ++stats.envelopes;
        boost::container::small_vector<Profile, 4> g;
        for (int s : G) g.push_back(profile(g_[s], p, q));
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
        const Vec2 mid{0.5 * (a.x + b.x), 0.5 * (a.y + b.y)};
        int u = across < 0 ? -1 : m_.axis_owner(G.data(), G.size(), across, *GP[0], mid, un);
        if (u < 0) u = m_.owner_beyond(mid, nrm, tied), ++stats.owners_evaluated;
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
    if (std::fabs(dp - f_[u].at(p.x, p.y)) > m_.tol(p) || std::fabs(dq - f_[u].at(q.x, q.y)) > m_.tol(q)) return;
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


  const Model& m_;  // the geometry: sites, distance functions, the ownership rule
  const SiteList& S_;
  const Box clip_;
  const Box hole_;
  const bool has_hole_;
  const BuildOptions opt_;
  const std::vector<DistFn>& f_;
  const std::vector<DistFn>& g_;
  const double tau_;
};

// The work counts of `from` added to `to` (a worker's, or the ended tiles'); the tiles'
// own counts (tiles, tasks, the largest tile) are kept by the caller.
void add_work(BuildStats& to, const BuildStats& from) {
  to.boxes += from.boxes, to.solves += from.solves, to.solved_sites += from.solved_sites;
  to.solved_pairs += from.solved_pairs, to.cells += from.cells, to.raw_pieces += from.raw_pieces;
  to.tie_cells += from.tie_cells, to.envelopes += from.envelopes, to.owners_evaluated += from.owners_evaluated;
}

// The workers' pieces, with global site ids, joined (about a third of the raw pieces remain),
// into `raw` (its capacity kept: tile after tile it is the same buffer, not fresh pages); their
// counts added to `st`.
void collect(const Model& m, const std::vector<Builder>& workers, BuildStats& st, std::vector<Piece>& raw) {
  std::size_t n = 0;
  for (const Builder& w : workers) n += w.out.size();
  raw.clear();
  raw.reserve(n);
  // A point of no width between two segments (zero_width.hpp): its pieces with the lower one
  // are the two segments' (as the sweep reports them), those with the other the same line again.
  for (const Builder& w : workers) {
    for (Piece p : w.out) {
      if (!m.partners.empty() && m.S[p.a].is_point() != m.S[p.b].is_point()) {
        const int pt = m.S[p.a].is_point() ? p.a : p.b, seg = pt == p.a ? p.b : p.a;
        const int end = end_at(m.S, seg, pt);
        const int other = end < 0 ? -1 : partner_at(m.partners, seg, end, ray_of(m.S[seg], end, p.p, p.q));
        if (other >= 0) {
          if (other < seg) continue;
          p.a = seg, p.b = other;
        }
      }
      p.a = m.global[p.a], p.b = m.global[p.b];
      raw.push_back(p);
    }
    add_work(st, w.stats);
  }
  st.raw_pieces += raw.size();
  join_pieces(raw);
}


}  // namespace
}  // namespace linf::detail
