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
#include <boost/multiprecision/cpp_int.hpp>
#include <cmath>
#include <cstdint>
#include <type_traits>

namespace linf::sweep {

// The coefficients' type I and that of their products, W. Points, axis-parallel and 45-degree
// lines keep the coefficients within 2^37: int64, products in 128 bits. A slanted line's row
// has its normal's size (up to 2^31), and the balls' coefficients reach 2^133: 256 bits,
// products in 512 (ball.hpp: the bounds).
using Int256 = boost::multiprecision::int256_t;
using Int512 = boost::multiprecision::int512_t;
template <typename I>
struct WideOf;
template <>
struct WideOf<std::int64_t> {
  using type = __int128;
};
template <>
struct WideOf<__int128> {
  using type = Int256;
};
template <>
struct WideOf<Int256> {
  using type = Int512;
};
// Whether a * b - c * d has a sign that the long-double products decide (the filter ahead of
// the exact wide products of the 128- and 256-bit tiers): 1 or -1, 0 if too close to call.
// Each conversion and product rounds by at most 2^-64 relative; 2^-58 of the magnitudes covers
// the four and the difference.
template <typename I>
int filtered_sign(const I& a, const I& b, const I& c, const I& d) {
  const long double l = static_cast<long double>(a) * static_cast<long double>(b),
                    r = static_cast<long double>(c) * static_cast<long double>(d);
  const long double tol = (std::fabs(l) + std::fabs(r)) * 0x1p-58L;
  if (l - r > tol) return 1;
  if (r - l > tol) return -1;
  return 0;
}
template <typename T>
double to_double(const T& v) {
  return static_cast<double>(v);
}

// Coefficients of eps^0 .. eps^3: what the predicates keep is at most cubic in eps (sweep's
// balls: linear sides, 3x3 determinants with one constant column), and for coordinates within
// +-2^30 its coefficients stay within 2^37. Products beyond degree 3 are only formed inside
// compare(), which keeps all seven orders.
constexpr int kTerms = 4;

template <typename I>
struct EpsT {
  using Eps = EpsT;
  std::array<I, kTerms> c{};
  EpsT() = default;
  EpsT(const I& v) { c[0] = v; }  // NOLINT: an integer is a constant polynomial
  static Eps of(const I& c0, const I& c1) {
    Eps e;
    e.c[0] = c0, e.c[1] = c1;
    return e;
  }
  int sign() const {
    for (const I& v : c)
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
  friend Eps operator*(const I& k, const Eps& a) {
    Eps r;
    for (int i = 0; i < kTerms; ++i) r.c[i] = k * a.c[i];
    return r;
  }
  // The value at eps = 0 (what a coordinate converges to).
  double limit() const { return to_double(c[0]); }
};
using Eps = EpsT<std::int64_t>;

// e (1 + eps), kept to kTerms orders as operator* keeps them: a shift and an add, where the
// product's loops cost a wide tier's events a few per cent.
template <typename I>
EpsT<I> times_one_plus_eps(const EpsT<I>& e) {
  EpsT<I> r;
  r.c[0] = e.c[0];
  for (int k = 1; k < kTerms; ++k) r.c[k] = e.c[k] + e.c[k - 1];
  return r;
}

// n / d rounded once, to the nearest double: the same rational gives the same bits whatever
// its representation (two balls of one vertex, a vertex and a bend of a bisector, in a tile and
// in the whole layer). An integer quotient of 62-63 bits with the remainder as a sticky bit,
// rounded by the conversion; magnitudes within 2^440.
inline double rounded_quotient(const Int512& n, const Int512& d) {
  if (n == 0) return 0.0;
  const bool negative = (n < 0) != (d < 0);
  const Int512 a = n < 0 ? Int512(-n) : n, b = d < 0 ? Int512(-d) : d;
  const int s = 62 + int(boost::multiprecision::msb(b)) - int(boost::multiprecision::msb(a));
  const Int512 num = s >= 0 ? Int512(a << s) : a, den = s >= 0 ? b : Int512(b << -s);
  const Int512 q = num / den;
  std::uint64_t bits = static_cast<std::uint64_t>(q);
  if (q * den != num) bits |= 1;  // sticky: q has more than 54 bits, so the round is the true one
  const double v = std::ldexp(double(bits), -s);
  return negative ? -v : v;
}
// The same for 128-bit integers, exact in doubles below 2^53.
inline double rounded_quotient(__int128 n, __int128 d) {
  const __int128 lim = __int128(1) << 53;
  if (n < lim && -n < lim && d < lim && -d < lim) return double(n) / double(d);
  return rounded_quotient(Int512(n), Int512(d));
}

// A ratio num / den with den > 0 at 0+.
template <typename I>
struct RatioT {
  using Int = I;
  using Eps = EpsT<I>;
  Eps num, den = Eps(I(1));
  RatioT() = default;
  RatioT(const I& v) : num(v) {}  // NOLINT
  RatioT(const Eps& n, const Eps& d) : num(n), den(d) {
    if (den.sign() < 0) num = -num, den = -den;
  }
  // The limit at eps -> 0+: the ratio of the lowest coefficients of the same order, where the
  // denominator's lowest order is at most the numerator's (what the predicates produce).
  double limit() const {
    const int k = order();
    return ratio_to_double(num.c[k], den.c[k]);
  }
  // The order limit() reads: the denominator's lowest nonzero one (the last if none).
  int order() const {
    int k = 0;
    while (k < kTerms - 1 && den.c[k] == 0) ++k;
    return k;
  }
  static double ratio_to_double(const I& n, const I& d) {
    if constexpr (std::is_same_v<I, std::int64_t>) return double(n) / double(d);  // within 2^53: one rounding
    else if constexpr (std::is_same_v<I, __int128>) return rounded_quotient(n, d);
    else return rounded_quotient(Int512(n), Int512(d));
  }
};
using Ratio = RatioT<std::int64_t>;

// Whether every coefficient lies within 2^60: then the sums of the products below (at most
// eight of two such factors) stay within 2^123, and 128 bits hold them exactly. Most of a
// 128-bit tier's numbers do (round pads: coordinates of 10^4 DBU, normals of 10^2), and the
// 128-bit products cost far less than the long-double filter's conversions or 256-bit ones.
template <typename I>
bool within60(const EpsT<I>& e) {
  const I lim = I(std::int64_t(1) << 60);
  for (const I& v : e.c)
    if (v > lim || v < -lim) return false;
  return true;
}

// The sign of a - b at 0+, exactly, with products in W.
template <typename W, typename I>
int compare_in(const RatioT<I>& a, const RatioT<I>& b) {
  const W l0 = W(a.num.c[0]) * W(b.den.c[0]), r0 = W(b.num.c[0]) * W(a.den.c[0]);
  if (l0 != r0) return l0 < r0 ? -1 : 1;
  bool same_den = true;  // term by term: std::array's == is a call to memcmp, 4% of a build
  for (int k = 0; k < kTerms; ++k) same_den = same_den && a.den.c[k] == b.den.c[k];
  if (same_den) {  // ties on the grid: often one denominator (or the same event)
    for (int k = 1; k < kTerms; ++k)
      if (a.num.c[k] != b.num.c[k]) return a.num.c[k] < b.num.c[k] ? -1 : 1;
    return 0;
  }
  for (int k = 1; k < 2 * kTerms - 1; ++k) {
    const int lo = std::max(0, k - kTerms + 1), hi = std::min(k, kTerms - 1);
    W v = 0;
    for (int i = lo; i <= hi; ++i) v += W(a.num.c[i]) * W(b.den.c[k - i]) - W(b.num.c[i]) * W(a.den.c[k - i]);
    if (v != 0) return v < 0 ? -1 : 1;
  }
  return 0;
}

// The sign of a - b at 0+. The constant terms decide almost always (one product each way).
template <typename I>
int compare(const RatioT<I>& a, const RatioT<I>& b) {
  if constexpr (std::is_same_v<I, std::int64_t>) {
    return compare_in<__int128>(a, b);
  } else {
    if constexpr (std::is_same_v<I, __int128>)
      if (within60(a.num) && within60(a.den) && within60(b.num) && within60(b.den)) return compare_in<__int128>(a, b);
    const int f = filtered_sign(a.num.c[0], b.den.c[0], b.num.c[0], a.den.c[0]);
    if (f != 0) return f;
    return compare_in<typename WideOf<I>::type>(a, b);
  }
}

// The sign at 0+ of a * d - b * c, every order kept, with products in W.
template <typename W, typename I>
int sign_of_cross_in(const EpsT<I>& a, const EpsT<I>& b, const EpsT<I>& c, const EpsT<I>& d) {
  for (int k = 0; k < 2 * kTerms - 1; ++k) {
    const int lo = std::max(0, k - kTerms + 1), hi = std::min(k, kTerms - 1);
    W v = 0;
    for (int i = lo; i <= hi; ++i) v += W(a.c[i]) * W(d.c[k - i]) - W(b.c[i]) * W(c.c[k - i]);
    if (v != 0) return v < 0 ? -1 : 1;
  }
  return 0;
}

// The sign at 0+ of a * d - b * c, every order kept (the four may be cubic).
template <typename I>
int sign_of_cross(const EpsT<I>& a, const EpsT<I>& b, const EpsT<I>& c, const EpsT<I>& d) {
  if constexpr (std::is_same_v<I, std::int64_t>) {
    return sign_of_cross_in<__int128>(a, b, c, d);
  } else {
    if constexpr (std::is_same_v<I, __int128>)
      if (within60(a) && within60(b) && within60(c) && within60(d)) return sign_of_cross_in<__int128>(a, b, c, d);
    const int f = filtered_sign(a.c[0], d.c[0], b.c[0], c.c[0]);
    if (f != 0) return f;
    return sign_of_cross_in<typename WideOf<I>::type>(a, b, c, d);
  }
}

}  // namespace linf::sweep
