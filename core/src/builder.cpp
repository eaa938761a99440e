#include "linf/builder.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "affine.hpp"
#include "cell.hpp"

namespace linf {
using detail::Affine;
using detail::Cell;
using detail::DistFn;

namespace {

Affine minus(const Affine& p, const Affine& q) { return {p.a - q.a, p.b - q.b, p.c - q.c}; }

// L-inf distance between a closed box and a site: zero if they meet, else attained at a vertex
// of one of them (both are convex polygons and the unit ball is a polygon).
// The same holds for L1, whose breakpoints along a segment are only the axis crossings.
double box_distance(const Box& b, const Site& s, bool l1 = false) {
  auto point_to_box = [&](double x, double y) {
    const double ex = std::max({b.x1 - x, x - b.x2, 0.0}), ey = std::max({b.y1 - y, y - b.y2, 0.0});
    return l1 ? ex + ey : std::max(ex, ey);
  };
  const double ax = double(s.a.x), ay = double(s.a.y), bx = double(s.b.x), by = double(s.b.y);
  double d = std::min(point_to_box(ax, ay), point_to_box(bx, by));
  if (s.is_point() || d == 0) return d;
  // Liang-Barsky: does the segment cross the box?
  double t0 = 0, t1 = 1;
  const double dx = bx - ax, dy = by - ay;
  auto edge = [&](double p, double q) {
    if (p == 0) return q >= 0;
    double r = q / p;
    if (p < 0) { if (r > t1) return false; t0 = std::max(t0, r); }
    else { if (r < t0) return false; t1 = std::min(t1, r); }
    return true;
  };
  if (edge(-dx, ax - b.x1) && edge(dx, b.x2 - ax) && edge(-dy, ay - b.y1) && edge(dy, b.y2 - ay)) return 0;
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
  std::vector<signed char> af, ag;  // active piece of f / g per local site, -1 unknown
};

class Builder {
 public:
  Builder(const Sites& s, const Box& clip, const BuildOptions& opt) : S_(s.sites), clip_(clip), opt_(opt) {
    f_.reserve(S_.size());
    g_.reserve(S_.size());
    double scale = 1;
    for (const Site& t : S_) {
      f_.push_back(detail::make_distfn(t, detail::Norm::Linf));
      g_.push_back(detail::make_distfn(t, detail::Norm::L1));
      scale = std::max({scale, std::fabs(double(t.a.x)), std::fabs(double(t.a.y)), std::fabs(double(t.b.x)),
                        std::fabs(double(t.b.y))});
    }
    scale = std::max({scale, std::fabs(clip.x1), std::fabs(clip.x2), std::fabs(clip.y1), std::fabs(clip.y2)});
    tau_ = 1e-12 * scale;
  }

  std::vector<Piece> run() {
    std::vector<int> all(S_.size());
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = int(i);
    process(clip_, all);
    return std::move(out_);
  }

 private:
  void process(const Box& b, const std::vector<int>& cand) {
    ++stats.boxes;
    double U = INFINITY;
    for (int t : cand) {
      const DistFn& f = f_[t];
      U = std::min(U, std::max({f.at(b.x1, b.y1), f.at(b.x2, b.y1), f.at(b.x2, b.y2), f.at(b.x1, b.y2)}));
    }
    std::vector<int> keep;
    keep.reserve(cand.size());
    for (int t : cand)
      if (box_distance(b, S_[t]) <= U + tau_) keep.push_back(t);
    if (keep.size() > 2) prune_ties(b, keep);
    if (keep.size() <= 1) return;
    const double w = std::max(b.x2 - b.x1, b.y2 - b.y1);
    // Far from the sites whole groups tie in L-inf (a two-dimensional bisector region) and the
    // count never drops; there the functions are affine over the box, so a direct solve is cheap.
    if (int(keep.size()) <= opt_.local_sites || w <= opt_.min_box ||
        (int(keep.size()) <= opt_.affine_sites && bent(b, keep) <= opt_.bent_sites)) {
      solve(b, keep);
      return;
    }
    const double mx = 0.5 * (b.x1 + b.x2), my = 0.5 * (b.y1 + b.y2);
    process({b.x1, b.y1, mx, my}, keep);
    process({mx, b.y1, b.x2, my}, keep);
    process({b.x1, my, mx, b.y2}, keep);
    process({mx, my, b.x2, b.y2}, keep);
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
      for (std::size_t i = g0; i < g1; ++i) {
        const DistFn& g = g_[flat[i].t];
        U = std::min(U, std::max({g.at(b.x1, b.y1), g.at(b.x2, b.y1), g.at(b.x2, b.y2), g.at(b.x1, b.y2)}));
      }
      // Members with identical L1 pieces are all kept: they may part just outside the box,
      // and the owner beyond a box side must be among the candidates.
      for (std::size_t i = g0; i < g1; ++i)
        if (box_distance(b, S_[flat[i].t], true) <= U + tau_) rest.push_back(flat[i].t);
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
    for (int t : C) {
      const DistFn& f = f_[t];
      const int j = f.argmax(b.x1, b.y1);
      if (f.argmax(b.x2, b.y1) != j || f.argmax(b.x2, b.y2) != j || f.argmax(b.x1, b.y2) != j) ++n;
    }
    return n;
  }

  // Splits `cells` so that site `fn` is affine on each; `act` selects af or ag.
  static void split_by(std::vector<LocalCell>& cells, const DistFn& fn, std::size_t k, bool use_g) {
    std::vector<LocalCell> next;
    next.reserve(cells.size());
    for (LocalCell& lc : cells) {
      auto& act = use_g ? lc.ag : lc.af;
      int j = fn.argmax(lc.cell.v[0].x, lc.cell.v[0].y);
      bool affine = true;
      for (const Vec2& p : lc.cell.v) {
        const double top = fn.at(p.x, p.y);
        if (fn.piece[j].at(p.x, p.y) < top - 16 * fn.piece[j].err(p.x, p.y)) { affine = false; break; }
      }
      if (affine) {
        act[k] = static_cast<signed char>(j);
        next.push_back(std::move(lc));
        continue;
      }
      for (int jj = 0; jj < fn.n; ++jj) {
        Cell c = lc.cell;
        for (int i = 0; i < fn.n && !c.empty(); ++i)
          if (i != jj) c = detail::clip(c, minus(fn.piece[jj], fn.piece[i]), Cell::kBoundary);
        if (c.empty()) continue;
        LocalCell sub{std::move(c), lc.af, lc.ag};
        (use_g ? sub.ag : sub.af)[k] = static_cast<signed char>(jj);
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
    for (std::size_t i = 0; i < k; ++i) split_by(cells, f_[C[i]], i, false);
    stats.cells += cells.size();

    for (LocalCell& lc : cells) {
      // Sites whose L-inf pieces coincide here need the L1 tie-break, hence affine L1 pieces.
      std::vector<LocalCell> sub{lc};
      std::vector<char> tied(k, 0);
      for (std::size_t i = 0; i < k; ++i)
        for (std::size_t j = i + 1; j < k; ++j)
          if (detail::same_affine(f_[C[i]].piece[lc.af[i]], f_[C[j]].piece[lc.af[j]])) tied[i] = tied[j] = 1;
      for (std::size_t i = 0; i < k; ++i)
        if (tied[i]) split_by(sub, g_[C[i]], i, true);
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
    for (std::size_t i = 0; i < k; ++i) {
      Cell r = lc.cell;
      for (std::size_t j = 0; j < k && !r.empty(); ++j) {
        if (j == i) continue;
        Affine h;
        int always = -1;
        if (compare(lc, C, i, j, h, always))
          r = detail::clip(r, h, C[j]);
        else if (!always)
          r = Cell{};
      }
      if (r.empty()) continue;
      emit(r, C[i], C);
    }
  }

  // Restriction of an affine piece to the edge p + s (q - p): value at s = 0 and slope.
  struct Line { double v, d; };
  static Line along(const Affine& a, const Vec2& p, const Vec2& q) {
    const double v = a.at(p.x, p.y);
    return {v, a.at(q.x, q.y) - v};
  }
  // A distance function restricted to an edge: a convex piecewise-linear function of s.
  struct Profile {
    Line L[6];
    int n = 0;
    double at(double s) const {
      double m = -INFINITY;
      for (int i = 0; i < n; ++i) m = std::max(m, L[i].v + s * L[i].d);
      return m;
    }
    bool active(int i, double s) const {
      const double v = L[i].v + s * L[i].d;
      return v >= at(s) - 1e-12 * (1 + std::fabs(v));
    }
  };
  static Profile profile(const DistFn& f, const Vec2& p, const Vec2& q) {
    Profile pr;
    pr.n = f.n;
    for (int i = 0; i < f.n; ++i) pr.L[i] = along(f.piece[i], p, q);
    return pr;
  }
  // Interior parameters where the two profiles' active pieces cross (one profile: its breaks).
  static void crossings(const Profile& A, const Profile& B, bool same, std::vector<double>& out) {
    for (int i = 0; i < A.n; ++i)
      for (int j = same ? i + 1 : 0; j < B.n; ++j) {
        const double dd = A.L[i].d - B.L[j].d;
        if (dd == 0) continue;
        const double s = (B.L[j].v - A.L[i].v) / dd;
        if (s > 1e-9 && s < 1 - 1e-9 && A.active(i, s) && B.active(j, s)) out.push_back(s);
      }
  }

  void emit(const Cell& r, int t, const std::vector<int>& C) {
    const std::size_t n = r.v.size();
    for (std::size_t e = 0; e < n; ++e) {
      const Vec2 p = r.v[e], q = r.v[(e + 1) % n];
      if (std::hypot(q.x - p.x, q.y - p.y) <= 1e-9) continue;
      const Vec2 nrm{q.y - p.y, p.x - q.x};
      const Vec2 m{0.5 * (p.x + q.x), 0.5 * (p.y + q.y)};
      if ((nrm.x < 0 && m.x <= clip_.x1) || (nrm.x > 0 && m.x >= clip_.x2) || (nrm.y < 0 && m.y <= clip_.y1) ||
          (nrm.y > 0 && m.y >= clip_.y2))
        continue;
      // The neighbour is found from this side, never from the edge's label: where several
      // sites tie in L-inf their bisector lines coincide, and the owner beyond can change
      // along the edge where the tie-break changes. Those places are among the crossings of
      // the affine pieces of the sites that reach t's distance somewhere on the edge.
      const Line ft = along(f_[t].piece[f_[t].argmax(m.x, m.y)], p, q);
      // Distances are 1-Lipschitz in L-inf: a site clearly farther at the midpoint never ties.
      const double reach = std::max(std::fabs(q.x - p.x), std::fabs(q.y - p.y)) + tol(p) + tol(q);
      const double fm = ft.v + 0.5 * ft.d;
      std::vector<Profile> g{profile(g_[t], p, q)};
      std::vector<double> cuts{0.0, 1.0};
      for (int u : C) {
        if (u == t || f_[u].at(m.x, m.y) - fm > reach) continue;
        const Profile fu = profile(f_[u], p, q);
        std::vector<double> breaks;
        crossings(fu, fu, true, breaks);
        double gap = std::min(fu.at(0) - ft.v, fu.at(1) - ft.v - ft.d);
        for (double s : breaks) gap = std::min(gap, fu.at(s) - (ft.v + s * ft.d));
        if (gap > tol(p) + tol(q)) continue;
        cuts.insert(cuts.end(), breaks.begin(), breaks.end());
        g.push_back(profile(g_[u], p, q));
      }
      if (g.size() == 1) continue;  // a split inside t's own region
      for (std::size_t i = 0; i < g.size(); ++i)
        for (std::size_t j = i; j < g.size(); ++j) crossings(g[i], g[j], i == j, cuts);
      std::sort(cuts.begin(), cuts.end());
      for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
        if (cuts[i + 1] - cuts[i] <= 1e-9) continue;
        const Vec2 a{p.x + cuts[i] * (q.x - p.x), p.y + cuts[i] * (q.y - p.y)};
        const Vec2 b{p.x + cuts[i + 1] * (q.x - p.x), p.y + cuts[i + 1] * (q.y - p.y)};
        emit_piece(a, b, t, owner_beyond({0.5 * (a.x + b.x), 0.5 * (a.y + b.y)}, nrm, C));
      }
    }
  }

  void emit_piece(const Vec2& p, const Vec2& q, int t, int u) {
    if (u == t || t > u) return;  // no edge, or the other side reports it
    if (std::fabs(f_[t].at(p.x, p.y) - f_[u].at(p.x, p.y)) > tol(p) ||
        std::fabs(f_[t].at(q.x, q.y) - f_[u].at(q.x, q.y)) > tol(q))
      return;
    Piece pc;
    pc.p = p, pc.q = q;
    pc.a = t, pc.b = u;
    pc.d1 = f_[t].at(p.x, p.y);
    pc.d2 = f_[t].at(q.x, q.y);
    out_.push_back(pc);
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
  int owner_beyond(const Vec2& m, const Vec2& d, const std::vector<int>& C) const {
    const double len = std::hypot(d.x, d.y);
    const Vec2 u{d.x / len, d.y / len};
    const double tl = tol(m);
    double fmin = INFINITY;
    for (int t : C) fmin = std::min(fmin, f_[t].at(m.x, m.y));
    int best = -1;
    double bs = 0, bg = 0, bgs = 0;
    for (int t : C) {
      const double fv = f_[t].at(m.x, m.y);
      if (fv > fmin + tl) continue;
      const double s = slope(f_[t], m, u, fv, tl);
      const double gv = g_[t].at(m.x, m.y);
      const double gs = slope(g_[t], m, u, gv, tl);
      bool better;
      if (best < 0) better = true;
      else if (std::fabs(s - bs) > 1e-12) better = s < bs;
      else if (std::fabs(gv - bg) > tl) better = gv < bg;
      else if (std::fabs(gs - bgs) > 1e-12) better = gs < bgs;
      else better = rank_before(t, best);
      if (better) best = t, bs = s, bg = gv, bgs = gs;
    }
    return best;
  }


 public:
  BuildStats stats;

 private:
  const std::vector<Site>& S_;
  Box clip_;
  BuildOptions opt_;
  std::vector<DistFn> f_, g_;
  double tau_ = 0;
  std::vector<Piece> out_;
};

// Joins pieces of the same two owners that continue each other in a straight line.
std::vector<Piece> join_pieces(std::vector<Piece> in) {
  std::sort(in.begin(), in.end(), [](const Piece& x, const Piece& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; });
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

}  // namespace

std::vector<Piece> build_pieces(const Sites& sites, const Box& clip, const BuildOptions& opt, BuildStats* stats) {
  if (sites.sites.size() < 2) return {};
  Builder b(sites, clip, opt);
  std::vector<Piece> raw = b.run();
  b.stats.raw_pieces = raw.size();
  if (stats) *stats = b.stats;
  return join_pieces(std::move(raw));
}

}  // namespace linf
