// Distance functions as maxima of affine pieces.
//
// For a convex site s and a norm with polygonal unit ball Q, the distance is
//   d(x, s) = max over normals n of (n.x - h_s(n)) / h_Q(n),
// taken over the edge normals of s (+) Q. Any extra normal only adds a piece that is
// nowhere above d, so we may use the fixed set below. With integer sites every piece has
// rational coefficients of small height, which keeps the builder's decisions well conditioned.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstdint>
#include <numeric>

#include "linf/geometry/site.hpp"

namespace linf::detail {

struct Affine {
  double a = 0, b = 0, c = 0;
  double at(double x, double y) const { return a * x + b * y + c; }
  // Rounding bound for evaluating at (x, y): a few ulps of the largest term.
  double err(double x, double y) const {
    return 1e-14 * (std::fabs(a * x) + std::fabs(b * y) + std::fabs(c) + 1.0);
  }
};

inline bool same_affine(const Affine& p, const Affine& q) {
  auto eq = [](double u, double v) { return std::fabs(u - v) <= 1e-12 * (1.0 + std::fabs(u) + std::fabs(v)); };
  return eq(p.a, q.a) && eq(p.b, q.b) && eq(p.c, q.c);
}

enum class Norm { Linf, L1 };

struct DistFn {
  Affine piece[6];
  int n = 0;
  // Four pieces (every L-inf function but a slanted edge's, every point's L1 function) are
  // unrolled: the builder evaluates these by the hundred million. The same order, the same maxima.
  double at(double x, double y) const {
    double m = piece[0].at(x, y);
    if (n == 4) return std::max(std::max(std::max(m, piece[1].at(x, y)), piece[2].at(x, y)), piece[3].at(x, y));
    for (int i = 1; i < n; ++i) m = std::max(m, piece[i].at(x, y));
    return m;
  }
  int argmax(double x, double y) const {
    int k = 0;
    double m = piece[0].at(x, y);
    auto take = [&](int i) {
      const double v = piece[i].at(x, y);
      if (v > m) m = v, k = i;
    };
    if (n == 4) {
      take(1), take(2), take(3);
      return k;
    }
    for (int i = 1; i < n; ++i) take(i);
    return k;
  }
};

// A segment neither axis-parallel nor at 45 degrees: its L1 tie-break is the farther of its
// ends' L1 distances (dist_site_l1), which is its own end's in the cone where that end is its
// L-inf nearest point (the end comes first there) but far above its true L1 distance inside
// its strip, so the builder never lets that tie-break stand in for an L-inf comparison within
// the allowance (Model::dominated).
inline bool steep_edge(const Site& s) {
  return !s.is_point() && s.a.x != s.b.x && s.a.y != s.b.y &&
         std::llabs(std::int64_t(s.b.x) - s.a.x) != std::llabs(std::int64_t(s.b.y) - s.a.y);
}

inline DistFn make_distfn(const Site& s, Norm norm) {
  std::int64_t normals[6][2];
  int k = 0;
  if (norm == Norm::Linf) {
    const std::int64_t q[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    for (auto& v : q) normals[k][0] = v[0], normals[k][1] = v[1], ++k;
  } else {
    const std::int64_t q[4][2] = {{1, 1}, {1, -1}, {-1, 1}, {-1, -1}};
    for (auto& v : q) normals[k][0] = v[0], normals[k][1] = v[1], ++k;
  }
  // A steep edge's L1 tie-break: the farther of its ends', the same four normals with the
  // nearer end's support.
  const bool steep_l1 = norm == Norm::L1 && steep_edge(s);
  if (!s.is_point() && !steep_l1) {
    std::int64_t dx = s.b.x - s.a.x, dy = s.b.y - s.a.y;
    std::int64_t g = std::gcd(dx < 0 ? -dx : dx, dy < 0 ? -dy : dy);
    dx /= g, dy /= g;
    bool in_q = false;
    for (int i = 0; i < 4; ++i) in_q |= (normals[i][0] * dx + normals[i][1] * dy == 0);  // normal already in Q
    if (!in_q) {
      normals[k][0] = -dy, normals[k][1] = dx, ++k;
      normals[k][0] = dy, normals[k][1] = -dx, ++k;
    }
  }
  DistFn f;
  f.n = k;
  for (int i = 0; i < k; ++i) {
    const double nx = double(normals[i][0]), ny = double(normals[i][1]);
    const double hq = norm == Norm::Linf ? std::fabs(nx) + std::fabs(ny) : std::max(std::fabs(nx), std::fabs(ny));
    const double ha = nx * double(s.a.x) + ny * double(s.a.y), hb = nx * double(s.b.x) + ny * double(s.b.y);
    const double hs = steep_l1 ? std::min(ha, hb) : std::max(ha, hb);
    f.piece[i] = {nx / hq, ny / hq, -hs / hq};
  }
  return f;
}

}  // namespace linf::detail
