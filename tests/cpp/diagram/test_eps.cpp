// The sweep's exact numbers (core/src/diagram/sweep/eps.hpp): the 128-bit tier's comparisons in
// 128-bit products where every coefficient lies within 2^60 agree with the 256-bit products.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>

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
