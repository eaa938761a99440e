#pragma once
#include <cmath>

namespace linf {

// std::llround (half away from zero) without its library call, which the compiler does not
// inline: the gauge sort and the stretch and context keys round millions of values. The same
// result everywhere: below 2^62 the cast truncates exactly, and v minus its integer part is
// exact (a subset of v's bits), so the comparison with one half decides as llround does;
// beyond, infinities and NaN (an absent score) go to llround itself.
inline long long round_half_away(double v) {
  if (!(std::fabs(v) < 0x1p62)) return std::llround(v);
  const long long t = static_cast<long long>(v);
  const double f = v - static_cast<double>(t);
  return t + (f >= 0.5) - (f <= -0.5);
}

}  // namespace linf
