// The geometry the builder decides with, apart from the algorithm (as a traits class): one
// tile's sites and their distance functions, the ownership rule (least L-inf distance, then
// least L1, then rank) and the tests built on it, with their rounding allowances. Internal to
// the builder (subdivision.hpp).
#pragma once
#include <algorithm>
#include <cmath>
#include <vector>

#include <boost/container/small_vector.hpp>

#include "affine.hpp"
#include "bounds.hpp"
#include "convex_cell.hpp"
#include "linf/diagram/builder.hpp"
#include "zero_width.hpp"

// Internal linkage, as subdivision.hpp (see there).
namespace linf::detail {
namespace {

// The sites of one tile and their distance functions, shared read-only by the workers.
// Local ids run in the order of the global ids (`global`), so every decision that compares
// site indices (the tie rule) is the same in any tile. Coordinates are relative to `origin`
// (shifted, bounds.hpp), the same in every tile.
struct Model {
  SiteList S;
  std::vector<int> global;
  BuildOptions opt;
  std::vector<DistFn> f, g;  // L-inf, and the L1 tie-break
  double tau = 0;            // rounding allowance in pruning decisions, the same in every tile
  Model(const SiteList& all, std::vector<int> ids, const BuildOptions& o, double tau_, const Point& origin)
      : global(std::move(ids)), opt(o), tau(tau_) {
    S.reserve(global.size());
    f.reserve(global.size());
    g.reserve(global.size());
    bool slanted = false;
    for (int i : global) {
      const Site t = shifted(all[i], origin);
      S.push_back(t);
      f.push_back(make_distfn(t, Norm::Linf));
      g.push_back(make_distfn(t, Norm::L1));
      slanted = slanted || (!t.is_point() && t.a.x != t.b.x && t.a.y != t.b.y);
    }
    if (slanted) partners = zero_width_partners(S);
  }
  // zero_width.hpp: each segment's partner at its ends, on each ray of no width of the point
  // there (empty on a Manhattan layer, where there is none to find).
  std::vector<Partners> partners;

  // The allowance of a decision at p: tau, the same in every tile, and rounding at p's scale.
  double tol(const Vec2& p) const { return tau + 1e-13 * (std::fabs(p.x) + std::fabs(p.y)); }

  // The piece of f beyond m in direction d: the steepest along d of the pieces within `tol`
  // of f's value there (at least the one attaining it).
  static const Affine& steepest(const DistFn& f, const Vec2& m, const Vec2& d, double value, double tol) {
    int best = 0;
    double s = -INFINITY;
    for (int i = 0; i < f.n; ++i) {
      if (f.piece[i].at(m.x, m.y) < value - tol) continue;
      const double di = f.piece[i].a * d.x + f.piece[i].b * d.y;
      if (di > s) s = di, best = i;
    }
    return f.piece[best];
  }
  // The derivative of f at m along d.
  static double slope(const DistFn& f, const Vec2& m, const Vec2& d, double value, double tol) {
    const Affine& p = steepest(f, m, d, value, tol);
    return p.a * d.x + p.b * d.y;
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
    for (int t : C) fmin = std::min(fmin, f[t].at(m.x, m.y));
    // The L1 value and slope only where the L-inf slopes tie (computed at most once a site).
    struct Candidate {
      int t = -1;
      double s = 0, gv = 0, gs = 0;
      bool has_g = false;
    };
    auto with_g = [&](Candidate& c) {
      if (!c.has_g) c.gv = g[c.t].at(m.x, m.y), c.gs = slope(g[c.t], m, u, c.gv, tl), c.has_g = true;
    };
    Candidate best;
    for (int t : C) {
      const double fv = f[t].at(m.x, m.y);
      if (fv > fmin + tl) continue;
      Candidate c;
      c.t = t;
      c.s = slope(f[t], m, u, fv, tl);
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

  bool rank_before(int a, int b) const {
    const bool pa = S[a].is_point(), pb = S[b].is_point();
    if (pa != pb) return pa;
    return a < b;
  }

  // The L1 tie-break between two sites with the same L-inf piece q on a cell, where both are
  // points or axis-parallel edges (a Manhattan layer's every site): q's gradient is along one
  // axis, and where q is such a site's L-inf distance, its L1 distance is q plus the distance
  // along the other axis to the site's extent on that axis (a point, or an edge's span). So
  // the tie-break is the 1-D one between the two extents, which do not overlap (sites do not
  // cross): the site on the same side of the midpoint of the gap between them comes first,
  // and on that line the rank decides, as where the extents are the same (a point and its
  // edge seen beyond the edge's end: equal L1 distances). A half-plane, where the general
  // rule splits the cell by every piece of both L1 functions: on the SRAM the cells' L-inf
  // ties are 4.57 million pairs of such sites, 2.65 million of them an edge and its own end.
  enum class Order { Unknown, HalfPlane, Equal };
  // HalfPlane: h >= 0 where s comes first, h = 0 on the midpoint's line.
  Order axis_order(int s, int t, const Affine& q, Affine& h) const {
    const int across = opt.axis_ties ? across_of(q) : -1;
    if (across < 0 || !rectilinear(S[s]) || !rectilinear(S[t])) return Order::Unknown;
    const Extent u = extent(S[s], across), v = extent(S[t], across);
    if (u == v) return Order::Equal;
    double m, sign;
    if (u.hi <= v.lo) m = 0.5 * (u.hi + v.lo), sign = -1;  // s below t: s first where the coordinate < m
    else if (v.hi <= u.lo) m = 0.5 * (v.hi + u.lo), sign = 1;
    else return Order::Unknown;
    h = across ? Affine{0, sign, -sign * m} : Affine{sign, 0, -sign * m};
    return Order::HalfPlane;
  }
  // The axis across an L-inf piece's gradient (0: x, 1: y), or -1 for a slanted edge's piece.
  static int across_of(const Affine& q) {
    if (q.b == 0 && std::fabs(q.a) == 1) return 1;
    if (q.a == 0 && std::fabs(q.b) == 1) return 0;
    return -1;
  }
  // A rectilinear site's extent on an axis: a point, or an edge's span.
  struct Extent {
    double lo, hi;
    bool operator==(const Extent& o) const { return lo == o.lo && hi == o.hi; }
  };
  static Extent extent(const Site& z, int across) {
    const double p = double(across ? z.a.y : z.a.x), r = double(across ? z.b.y : z.b.x);
    return {std::min(p, r), std::max(p, r)};
  }

  // The L1 tie-break along an edge p -> q of a region, between the sites g[0, n) that tie
  // there in L-inf with the same least slope across it (Builder::emit; piece[i]: g[i]'s piece
  // beyond the edge's midpoint; fp, fq and tp, tq: the tied value and its allowance at the
  // edge's ends), where all are points or axis-parallel edges and one L-inf piece, the same for
  // all, is each one's distance along the whole edge and just beyond it. Then, as in
  // axis_order, each one's L1 distance along the edge is that piece plus the distance across to
  // its extent, and the nearest extent is the owner beyond (equal extents: the rank). So it
  // changes only where the edge crosses the midpoint of the gap between neighbouring extents:
  // those parameters in (0, 1) go to `cuts`, where the general rule walks the lower envelope
  // of the sites' L1 profiles and cuts at every breakpoint of them. Returns the axis across
  // (0: x, 1: y) for axis_owner, or -1, and `cuts` untouched, where this does not apply.
  template <class Cuts>
  int axis_cuts(const int* g, const Affine* const* piece, std::size_t n, const Vec2& p, const Vec2& q, double fp,
                double fq, double tp, double tq, Cuts& cuts) const {
    if (!opt.axis_ties) return -1;
    for (std::size_t i = 0; i < n; ++i) {
      if (!rectilinear(S[g[i]])) return -1;
      const Affine& pc = *piece[i];
      if (std::fabs(pc.at(p.x, p.y) - fp) > tp || std::fabs(pc.at(q.x, q.y) - fq) > tq) return -1;
      if (i && !same_affine(*piece[0], pc)) return -1;
    }
    const int across = across_of(*piece[0]);
    if (across < 0) return -1;
    // Sorted by inserting: mostly two or three (an edge and its end), where std::sort's
    // machinery cost more than the rest of the test.
    boost::container::small_vector<Extent, 8> ext(n, boost::container::default_init);
    for (std::size_t i = 0; i < n; ++i) {
      const Extent e = extent(S[g[i]], across);
      std::size_t j = i;
      for (; j > 0 && (e.lo < ext[j - 1].lo || (e.lo == ext[j - 1].lo && e.hi < ext[j - 1].hi)); --j) ext[j] = ext[j - 1];
      ext[j] = e;
    }
    for (std::size_t i = 1; i < n; ++i)
      if (!(ext[i] == ext[i - 1]) && ext[i].lo < ext[i - 1].hi) return -1;
    const double bp = across ? p.y : p.x, bq = across ? q.y : q.x;
    if (bp == bq) return across;  // the edge runs along the gradient: the distances across are constant
    for (std::size_t i = 1; i < n; ++i) {
      if (ext[i] == ext[i - 1]) continue;
      const double s = (0.5 * (ext[i - 1].hi + ext[i].lo) - bp) / (bq - bp);
      if (s > 1e-12 && s < 1 - 1e-12) cuts.push_back(s);
    }
    return across;
  }

  // owner_beyond's answer at m (direction u, a unit vector) among the sites g[0, n) of an edge
  // that axis_cuts took (`shared`: their L-inf piece, `across` its axis): their L1 distances
  // there are `shared` plus the distance across to their extents, so those are what is
  // compared (within the allowance), then their slopes along u (of the L1 pieces within the
  // allowance, as Model::slope takes them), then the rank, without evaluating the functions.
  // -1 within a few allowances of the sites, where the other halves of their L1 functions come
  // within the allowance too: owner_beyond decides there.
  int axis_owner(const int* g, std::size_t n, int across, const Affine& shared, const Vec2& m, const Vec2& u) const {
    const double tl = tol(m);
    if (shared.at(m.x, m.y) <= 4 * tl) return -1;
    const double c = across ? m.y : m.x, dir = across ? u.y : u.x;
    int best = -1;
    double bv = 0, bs = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const Extent e = extent(S[g[i]], across);
      // The L1 pieces beyond m, less `shared`: below the extent, above it, and along it (an
      // edge's own piece, where its extent across is not a point).
      const double below = e.lo - c, above = c - e.hi, v = std::max({below, above, 0.0});
      double s = -INFINITY;
      if (below >= v - tl) s = std::max(s, -dir);
      if (above >= v - tl) s = std::max(s, dir);
      if (e.lo < e.hi && v <= tl) s = std::max(s, 0.0);
      bool better;
      if (best < 0) better = true;
      else if (std::fabs(v - bv) > tl) better = v < bv;
      else if (std::fabs(s - bs) > 1e-12) better = s < bs;
      else better = rank_before(g[i], best);
      if (better) best = g[i], bv = v, bs = s;
    }
    return best;
  }

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
    const double m = 1e-3 * std::max(b.x2 - b.x1, b.y2 - b.y1) + tau;
    r.c[0] = {b.x1 - m, b.y1 - m}, r.c[1] = {b.x2 + m, b.y1 - m}, r.c[2] = {b.x2 + m, b.y2 + m}, r.c[3] = {b.x1 - m, b.y2 + m};
    for (int k = 0; k < 4; ++k)
      r.fu[k] = f[u].at(r.c[k].x, r.c[k].y), r.gu[k] = g[u].at(r.c[k].x, r.c[k].y), r.e[k] = tol(r.c[k]);
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
  // Where each piece of f_t is below f_u at some corner (Below), f_t may still be at least f_u
  // everywhere, each piece of f_u being under a different piece of f_t: a row of line ends
  // seen along the 45-degree line from its end, where the row's far ends tie in L-inf with the
  // near end on one side of the line only. That case is tested piece by piece, only once the L1
  // test has passed (rarely, for a site that is not dominated).
  bool dominated(const Reference& r, int t) const {
    if (r.u < 0 || t == r.u) return false;
    // Nearer than u at a corner: neither test below could pass (each compares these values),
    // and three in four sites tested are (the SRAM: 5.08 of 6.91 million).
    if (rectilinear(S[t]) && nearer_at_a_corner(S[t], r)) return false;
    const Side side = against(t, r.c, 4, r.fu, r.e);
    if (side == Side::Above) return true;
    // f_t within the allowance of f_u and g_t above g_u: a steep edge's g is no guide there
    // (affine.hpp, steep_edge): beside its end's cone it is nearer by less than the allowance.
    if (steep_edge(S[t]) || steep_edge(S[r.u])) return false;
    if (against(g[t], r.c, 4, r.gu, r.e) != Side::Above) return false;
    return side == Side::Neither || covers(f[t], r);
  }

  // A point or an axis-parallel edge z below the reference at a corner, beyond the allowance:
  // its L-inf distance there from its box's sides (the same doubles as its pieces give).
  static bool nearer_at_a_corner(const Site& z, const Reference& r) {
    const Sides b = sides(z);
    for (int k = 0; k < 4; ++k) {
      const Vec2& p = r.c[k];
      const double v = std::max(std::max(p.x - b.x2, b.x1 - p.x), std::max(p.y - b.y2, b.y1 - p.y));
      if (v - r.fu[k] < -r.e[k]) return true;
    }
    return false;
  }

  // Is every piece of f_u under some piece of fn at every corner, within the allowance? Both
  // are affine, so then on the whole grown box, and fn >= f_u - allowance there. Rare: the
  // pieces' values are computed here, not with every box's reference.
  bool covers(const DistFn& fn, const Reference& r) const {
    const DistFn& fu = f[r.u];
    double at[6][4], ref[6][4];
    for (int k = 0; k < 4; ++k) {
      for (int i = 0; i < fn.n; ++i) at[i][k] = fn.piece[i].at(r.c[k].x, r.c[k].y);
      for (int j = 0; j < fu.n; ++j) ref[j][k] = fu.piece[j].at(r.c[k].x, r.c[k].y);
    }
    for (int j = 0; j < fu.n; ++j) {
      bool under = false;
      for (int i = 0; i < fn.n && !under; ++i) {
        under = true;
        for (int k = 0; k < 4 && under; ++k) under = at[i][k] - ref[j][k] >= -r.e[k];
      }
      if (!under) return false;
    }
    return true;
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

  // A point's or an axis-parallel edge's box, whose sides give its L-inf pieces' values.
  struct Sides { double x1, x2, y1, y2; };
  static Sides sides(const Site& z) {
    return {double(std::min(z.a.x, z.b.x)), double(std::max(z.a.x, z.b.x)), double(std::min(z.a.y, z.b.y)),
            double(std::max(z.a.y, z.b.y))};
  }

  // against() for a point or an axis-parallel edge z, whose L-inf pieces are x - X2, X1 - x,
  // y - Y2 and Y1 - y over its box [X1, X2] x [Y1, Y2]: their values are differences of
  // coordinates (the same doubles as the pieces give). It runs for most candidates of every
  // box and every site of every cell.
  static Side against_rect(const Site& z, const Vec2* pts, std::size_t n, const double* ref,
                           const double* allowance) {
    const Sides b = sides(z);
    const double X1 = b.x1, X2 = b.x2, Y1 = b.y1, Y2 = b.y2;
    // As against(): a piece is given up at the first point where it is not above and some
    // point where it is below (most pieces, at their first or second point).
    bool below = true;
    auto piece = [&](auto value) {
      bool above = true, under = false;
      for (std::size_t k = 0; k < n; ++k) {
        const double d = value(pts[k]) - ref[k];
        above = above && d > allowance[k];
        under = under || d < -allowance[k];
        if (!above && under) break;
      }
      below = below && under;
      return above;
    };
    if (piece([X2](const Vec2& p) { return p.x - X2; }) || piece([X1](const Vec2& p) { return X1 - p.x; }) ||
        piece([Y2](const Vec2& p) { return p.y - Y2; }) || piece([Y1](const Vec2& p) { return Y1 - p.y; }))
      return Side::Above;
    return below ? Side::Below : Side::Neither;
  }
  Side against(int t, const Vec2* pts, std::size_t n, const double* ref, const double* allowance) const {
    return rectilinear(S[t]) ? against_rect(S[t], pts, n, ref, allowance) : against(f[t], pts, n, ref, allowance);
  }

  // The piece of f that is the maximum at every corner of the box, or -1.
  static int affine_piece(const DistFn& f, const Box& b) {
    const int j = f.argmax(b.x1, b.y1);
    if (f.argmax(b.x2, b.y1) != j || f.argmax(b.x2, b.y2) != j || f.argmax(b.x1, b.y2) != j) return -1;
    return j;
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
};

}  // namespace
}  // namespace linf::detail
