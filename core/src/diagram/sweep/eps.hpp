// Numbers of the sweep's predicates: polynomials in an infinitesimal eps > 0.
//
// The ownership rule (least L-inf distance, then least L1) is the limit, as eps -> 0+, of the
// norm N_eps = L-inf + eps L1, whose unit ball is an octagon with no side parallel to a line
// through two integer points. The sweep decides everything in N_eps for an infinitesimal eps:
// every quantity it compares is a polynomial in eps with integer coefficients (or a ratio of
// two), and its sign at 0+ is that of its lowest nonzero coefficient. Exact, and no case
// analysis of the ties: they are what the higher coefficients decide.
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>

namespace linf::sweep {

// Coefficients of eps^0 .. eps^3: what the predicates keep is at most cubic in eps (sweep's
// balls: linear sides, 3x3 determinants with one constant column), and for coordinates within
// +-2^30 its coefficients stay within 2^37. Products beyond degree 3 are only formed inside
// compare(), which keeps all seven orders.
constexpr int kTerms = 4;

struct Eps {
  std::array<std::int64_t, kTerms> c{};
  Eps() = default;
  Eps(std::int64_t v) { c[0] = v; }  // NOLINT: an integer is a constant polynomial
  static Eps of(std::int64_t c0, std::int64_t c1) {
    Eps e;
    e.c[0] = c0, e.c[1] = c1;
    return e;
  }
  int sign() const {
    for (std::int64_t v : c)
      if (v != 0) return v > 0 ? 1 : -1;
    return 0;
  }
  friend Eps operator+(const Eps& a, const Eps& b) {
    Eps r;
    for (int i = 0; i < kTerms; ++i) r.c[i] = a.c[i] + b.c[i];
    return r;
  }
  friend Eps operator-(const Eps& a, const Eps& b) {
    Eps r;
    for (int i = 0; i < kTerms; ++i) r.c[i] = a.c[i] - b.c[i];
    return r;
  }
  friend Eps operator-(const Eps& a) {
    Eps r;
    for (int i = 0; i < kTerms; ++i) r.c[i] = -a.c[i];
    return r;
  }
  friend Eps operator*(const Eps& a, const Eps& b) {
    Eps r;
    int da = kTerms - 1, db = kTerms - 1;
    while (da > 0 && a.c[da] == 0) --da;
    while (db > 0 && b.c[db] == 0) --db;
    for (int i = 0; i <= da; ++i) {
      if (a.c[i] == 0) continue;
      for (int j = 0; j <= db && i + j < kTerms; ++j) r.c[i + j] += a.c[i] * b.c[j];
    }
    return r;
  }
  friend Eps operator*(std::int64_t k, const Eps& a) {
    Eps r;
    for (int i = 0; i < kTerms; ++i) r.c[i] = k * a.c[i];
    return r;
  }
  // The value at eps = 0 (what a coordinate converges to).
  double limit() const { return double(c[0]); }
};

// A ratio num / den with den > 0 at 0+.
struct Ratio {
  Eps num, den = Eps(1);
  Ratio() = default;
  Ratio(std::int64_t v) : num(v) {}  // NOLINT
  Ratio(const Eps& n, const Eps& d) : num(n), den(d) {
    if (den.sign() < 0) num = -num, den = -den;
  }
  // The limit at eps -> 0+: the ratio of the lowest coefficients of the same order, where the
  // denominator's lowest order is at most the numerator's (what the predicates produce).
  double limit() const {
    int k = 0;
    while (k < kTerms - 1 && den.c[k] == 0) ++k;
    return double(num.c[k]) / double(den.c[k]);
  }
};

// The sign of a - b at 0+. The constant terms decide almost always (one product each way).
inline int compare(const Ratio& a, const Ratio& b) {
  const __int128 l0 = __int128(a.num.c[0]) * b.den.c[0], r0 = __int128(b.num.c[0]) * a.den.c[0];
  if (l0 != r0) return l0 < r0 ? -1 : 1;
  if (a.den.c == b.den.c) {  // ties on the grid: often one denominator (or the same event)
    for (int k = 1; k < kTerms; ++k)
      if (a.num.c[k] != b.num.c[k]) return a.num.c[k] < b.num.c[k] ? -1 : 1;
    return 0;
  }
  for (int k = 1; k < 2 * kTerms - 1; ++k) {
    __int128 v = 0;
    for (int i = std::max(0, k - kTerms + 1); i <= std::min(k, kTerms - 1); ++i)
      v += __int128(a.num.c[i]) * b.den.c[k - i] - __int128(b.num.c[i]) * a.den.c[k - i];
    if (v != 0) return v < 0 ? -1 : 1;
  }
  return 0;
}

// The sign at 0+ of a * d - b * c, every order kept (the four may be cubic).
inline int sign_of_cross(const Eps& a, const Eps& b, const Eps& c, const Eps& d) {
  for (int k = 0; k < 2 * kTerms - 1; ++k) {
    __int128 v = 0;
    for (int i = std::max(0, k - kTerms + 1); i <= std::min(k, kTerms - 1); ++i)
      v += __int128(a.c[i]) * d.c[k - i] - __int128(b.c[i]) * c.c[k - i];
    if (v != 0) return v < 0 ? -1 : 1;
  }
  return 0;
}

}  // namespace linf::sweep
