// The sweep's circle events: Boost's circle_event for our Ratio coordinates, specialised.
//
// Boost's generic event holds three coordinates (centre x, centre y, lower x). Ours are ratios
// of eps-polynomials, 64 bytes each in the int64 tier: a 200-byte event, copied into the event
// list and compared by exact 128-bit products every time the queue's heap moves. This one
// keeps what the sweep decides with exactly (lower x and centre y: numerators and the shared
// denominator), of the centre's x only what its limit needs (the vertex's place, output
// only), and double keys of lower x and y for the queue's order. The keys decide a comparison
// unless two lie within rounding of each other; then the exact ratios do. Same order, same
// events, same bits.
#pragma once
#include <boost/polygon/detail/voronoi_structures.hpp>
#include <cmath>
#include <limits>

#include "diagram/sweep/eps.hpp"

namespace linf::sweep {

// The sign of a - b where a and b are keys (key_of): each within a few units in the last place
// of the exact limit it stands for (two conversions and a quotient; a wide conversion may
// truncate); 0 if that cannot tell, also for a NaN or an infinity. The margin, 2^-48 of their
// size, is several times what those roundings can take together.
inline int filtered_limits(double a, double b) {
  const double tol = (std::fabs(a) + std::fabs(b)) * 0x1p-48;
  if (a - b > tol) return 1;
  if (b - a > tol) return -1;
  return 0;
}

// The limit of n / d at 0+ as the quotient of the two coefficients' doubles (no wide division:
// a key is made for every event, most of which are never processed), or NaN where the limit
// is no finite number (n of a lower order than d: the predicates never make one, and then the
// exact comparison decides).
template <typename I>
double key_of(const RatioT<I>& r) {
  const int k = r.order();
  for (int j = 0; j < k; ++j)
    if (r.num.c[j] != 0) return std::numeric_limits<double>::quiet_NaN();
  if (r.den.c[k] == 0) return std::numeric_limits<double>::quiet_NaN();
  return to_double(r.num.c[k]) / to_double(r.den.c[k]);
}

}  // namespace linf::sweep

namespace boost::polygon::detail {

template <typename I>
class circle_event<linf::sweep::RatioT<I>> {
 public:
  using coordinate_type = linf::sweep::RatioT<I>;
  using Eps = linf::sweep::EpsT<I>;

  circle_event() = default;
  // The ball of centre (cx, cy) / den and radius r / den; its event is where the sweep touches
  // its rightmost point, at x = (cx (1 + eps) + r) / (den (1 + eps)).
  circle_event(const Eps& cx, const Eps& cy, const Eps& r, const Eps& den) {
    using linf::sweep::times_one_plus_eps;
    const coordinate_type lower(times_one_plus_eps(cx) + r, times_one_plus_eps(den)), y(cy, den);
    lower_num_ = lower.num, lower_den_ = lower.den, y_num_ = y.num;
    x_num_ = coordinate_type(cx, den).num.c[y.order()];
    lower_key_ = linf::sweep::key_of(lower);
    y_key_ = linf::sweep::key_of(y);
  }

  coordinate_type lower_x() const { return {lower_num_, lower_den_}; }
  // The centre's y over den: den (1 + eps) is lower x's denominator (its orders up to
  // kTerms - 1 are den's plus the order below, so den comes back from them exactly), and its
  // sign is den's, so both were normalised alike.
  coordinate_type y() const {
    coordinate_type r;
    r.num = y_num_;
    r.den.c[0] = lower_den_.c[0];
    for (int k = 1; k < linf::sweep::kTerms; ++k) r.den.c[k] = lower_den_.c[k] - r.den.c[k - 1];
    return r;
  }
  // The vertex, as RatioT::limit rounds it (once, in the wide tiers): only for events processed.
  double x_limit() const {
    const coordinate_type y_ratio = y();
    return coordinate_type::ratio_to_double(x_num_, y_ratio.den.c[y_ratio.order()]);
  }
  double y_limit() const { return y().limit(); }
  double lower_x_key() const { return lower_key_; }
  double y_key() const { return y_key_; }

  bool is_active() const { return is_active_; }
  circle_event& deactivate() {
    is_active_ = false;
    return *this;
  }

 private:
  Eps lower_num_, lower_den_, y_num_;
  I x_num_{};  // the centre's x numerator at the order its limit reads (RatioT::order): all it needs
  double lower_key_ = 0, y_key_ = 0;
  bool is_active_ = true;
};

}  // namespace boost::polygon::detail
