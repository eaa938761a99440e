// The L1 tie-break along one edge of a region: each tied site's L1 distance restricted to the
// edge is a convex piecewise-linear profile, and the owner beyond the edge can change only
// where their lower envelope changes hands. Internal to the builder (subdivision.hpp).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstddef>

#include <boost/container/small_vector.hpp>

#include "affine.hpp"
#include "linf/geometry/piece.hpp"

// Internal linkage, as subdivision.hpp (see there).
namespace linf::detail {
namespace {

// Restriction of an affine piece to the edge p + s (q - p): value at s = 0 and slope.
struct Line { double v, d; };
Line along(const Affine& a, const Vec2& p, const Vec2& q) {
  const double v = a.at(p.x, p.y);
  return {v, a.at(q.x, q.y) - v};
}
// A distance function restricted to an edge: a convex piecewise-linear function of s on
// [0, 1], kept as its breakpoints and the line active after each.
struct Profile {
  boost::container::small_vector<double, 6> at;  // at[0] = 0 < at[1] < ... < 1
  boost::container::small_vector<Line, 6> line;
};
double eps(double v) { return 1e-11 * (1 + std::fabs(v)); }

// Where pieces tie at a breakpoint (an edge starting on a crease of the function: the edge's
// end computed a rounding away from it), the profile goes on with the steepest of them: the
// highest alone may be the one that falls away at once, and a steeper line overtaking it
// within 1e-12 of the start was not looked for, so the profile kept the wrong line over the
// whole edge (an L1 tie-break cut 2 DBU off, found as tiles and one pass disagreeing).
Profile profile(const DistFn& f, const Vec2& p, const Vec2& q) {
  Line L[6];
  for (int i = 0; i < f.n; ++i) L[i] = along(f.piece[i], p, q);
  Profile pr;
  double s = 0;
  int cur = 0;
  for (int i = 1; i < f.n; ++i)
    if (L[i].v > L[cur].v) cur = i;
  const double top = L[cur].v;
  for (int i = 0; i < f.n; ++i)  // the steepest among those tied with the highest at 0
    if (L[i].v >= top - eps(top) && L[i].d > L[cur].d) cur = i;
  for (;;) {
    pr.at.push_back(s), pr.line.push_back(L[cur]);
    int nxt = -1;
    double ns = 1;
    for (int i = 0; i < f.n; ++i) {  // the first steeper line to overtake; at a tie, the steepest
      if (L[i].d <= L[cur].d) continue;
      const double x = (L[cur].v - L[i].v) / (L[i].d - L[cur].d);
      if (x <= s + 1e-12) continue;
      if (x < ns - 1e-12 || (x <= ns + 1e-12 && nxt >= 0 && L[i].d > L[nxt].d)) ns = std::min(ns, x), nxt = i;
    }
    if (nxt < 0 || ns >= 1 - 1e-12) break;
    s = ns, cur = nxt;
  }
  return pr;
}
std::size_t line_after(const Profile& P, double s) {
  std::size_t i = 0;
  while (i + 1 < P.at.size() && P.at[i + 1] <= s) ++i;
  return i;
}
double value(const Profile& P, double s) {
  const Line& l = P.line[line_after(P, s)];
  return l.v + l.d * s;
}
// The first parameter in (s, 1) where B drops below A, or 1.
double first_below(const Profile& A, const Profile& B, double s) {
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
void envelope_cuts(const Profiles& P, Cuts& out) {
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

}  // namespace
}  // namespace linf::detail
