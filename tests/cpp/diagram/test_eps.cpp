// The sweep's exact numbers (core/src/diagram/sweep/eps.hpp): the 128-bit tier's comparisons in
// 128-bit products where every coefficient lies within 2^60 agree with the 256-bit products; the
// circle events' double keys agree with the exact order.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>

#include "diagram/sweep/circle.hpp"
#include "diagram/sweep/eps.hpp"

using namespace linf::sweep;

namespace {

using I = __int128;

// A coefficient of about `bits` bits, either sign (0 now and then: the ties of the higher orders).
I coefficient(std::mt19937_64& rng, int bits) {
  const std::uint64_t r = rng();
  if (r % 7 == 0) return 0;
  I v = I(rng() >> (64 - bits)) | 1;
  if (bits > 63) v = (v << (bits - 63)) | I(rng() >> (127 - bits));
  return r % 2 ? v : -v;
}

EpsT<I> polynomial(std::mt19937_64& rng, int bits) {
  EpsT<I> e;
  for (I& c : e.c) c = coefficient(rng, bits);
  return e;
}

}  // namespace

TEST(SweepNumbers, NarrowProductsAgreeWithWideOnesAroundTheLimit) {
  // Coefficients of 58 to 63 bits: below 2^60 the narrow products decide, above it the wide
  // ones (a limit raised to 2^63 overflows the sums of eight products and disagrees here).
  std::mt19937_64 rng(7);
  int narrow = 0, disagree = 0;
  for (int n = 0; n < 200000; ++n) {
    const int bits = 58 + n % 6;
    RatioT<I> a(polynomial(rng, bits), polynomial(rng, bits)), b(polynomial(rng, bits), polynomial(rng, bits));
    if (a.den.sign() == 0 || b.den.sign() == 0) continue;
    if (n % 3 == 0) b.num.c[0] = a.num.c[0], b.den.c[0] = a.den.c[0];  // the constant terms tie
    if (n % 5 == 0) b.den = a.den;                                      // one denominator
    narrow += within60(a.num) && within60(a.den) && within60(b.num) && within60(b.den);
    disagree += compare(a, b) != compare_in<Int256>(a, b);
    const EpsT<I> p = polynomial(rng, bits), q = polynomial(rng, bits), r = polynomial(rng, bits);
    const EpsT<I> s = n % 4 == 0 ? p : polynomial(rng, bits);
    disagree += sign_of_cross(p, q, r, s) != sign_of_cross_in<Int256>(p, q, r, s);
  }
  EXPECT_EQ(disagree, 0);
  EXPECT_GT(narrow, 10000);  // both paths taken
  EXPECT_LT(narrow, 150000);
}

// The circle events' keys (circle.hpp): the doubles decide only where the exact ratios agree,
// and the event keeps lower x and y exactly as the ratios it was made from. Coefficients of up
// to 62 bits, so that the int64 limits round up to three times, and pairs a unit apart.
TEST(SweepNumbers, CircleEventKeysOrderAsTheExactRatios) {
  using L = std::int64_t;
  using Circle = boost::polygon::detail::circle_event<RatioT<L>>;
  std::mt19937_64 rng(11);
  auto coefficient = [&](int bits) -> L {
    const L v = L(rng() >> (64 - bits));
    return rng() % 2 ? v : -v;
  };
  auto ball = [&](int bits, EpsT<L>& cx, EpsT<L>& cy, EpsT<L>& r, EpsT<L>& den) {
    for (int k = 0; k < 3; ++k) cx.c[k] = coefficient(bits), cy.c[k] = coefficient(bits), den.c[k] = coefficient(bits);
    for (int k = 0; k < 4; ++k) r.c[k] = coefficient(bits);
    cx.c[3] = cy.c[3] = den.c[3] = 0;
    if (rng() % 5 == 0) den.c[0] = 0, cx.c[0] = 0, r.c[0] = 0;  // a system singular at eps = 0
    if (rng() % 7 == 0) den.c[0] = 0;                           // no finite limit: NaN keys
  };
  const EpsT<L> one_eps = EpsT<L>::of(1, 1);
  int decided = 0, wrong = 0, unequal = 0;
  for (int n = 0; n < 200000; ++n) {
    const int bits = n % 2 ? 30 : 60;
    EpsT<L> cx[2], cy[2], r[2], den[2];
    ball(bits, cx[0], cy[0], r[0], den[0]);
    ball(bits, cx[1], cy[1], r[1], den[1]);
    if (n % 3 == 0) cx[1] = cx[0], r[1] = r[0], den[1] = den[0], cx[1].c[0] += L(n % 5) - 2;  // a unit apart
    if (n % 3 == 1 && bits == 60) {  // the same ball scaled by 3, then a unit apart: other roundings of nearly one value
      for (int k = 0; k < 4; ++k) cx[1].c[k] = 3 * (cx[0].c[k] /= 8), r[1].c[k] = 3 * (r[0].c[k] /= 8), den[1].c[k] = 3 * (den[0].c[k] /= 8);
      cy[1] = cy[0], cx[1].c[0] += L(n % 5) - 2;
    }
    if (n % 4 == 0) cy[1] = cy[0], cy[1].c[0] += L(n % 3) - 1;
    Circle c[2];
    for (int i = 0; i < 2; ++i) {
      if (den[i].sign() == 0) den[i].c[2] = 1;
      c[i] = Circle(cx[i], cy[i], r[i], den[i]);
      const RatioT<L> lower(cx[i] * one_eps + r[i], den[i] * one_eps), y(cy[i], den[i]);
      unequal += c[i].lower_x().num.c != lower.num.c || c[i].lower_x().den.c != lower.den.c;
      unequal += c[i].y().num.c != y.num.c || c[i].y().den.c != y.den.c;
      const double x = RatioT<L>(cx[i], den[i]).limit(), yl = y.limit();  // the vertex, bit for bit
      unequal += !(c[i].x_limit() == x || (x != x && c[i].x_limit() != c[i].x_limit()));
      unequal += !(c[i].y_limit() == yl || (yl != yl && c[i].y_limit() != c[i].y_limit()));
    }
    const int fx = filtered_limits(c[0].lower_x_key(), c[1].lower_x_key());
    const int fy = filtered_limits(c[0].y_key(), c[1].y_key());
    decided += (fx != 0) + (fy != 0);
    wrong += (fx != 0 && fx != compare(c[0].lower_x(), c[1].lower_x())) + (fy != 0 && fy != compare(c[0].y(), c[1].y()));
  }
  EXPECT_EQ(unequal, 0);
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(decided, 100000);  // the keys decide most, and the exact ratios the rest
  EXPECT_LT(decided, 380000);
}
