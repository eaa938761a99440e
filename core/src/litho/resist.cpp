// Threshold crossings along a measurement line (resist.hpp).
#include "linf/litho/resist.hpp"

#include <cmath>
#include <stdexcept>

namespace linf::litho {
namespace {

// A root of f in [a, b] where f(a), f(b) have opposite signs (fa, fb their values): the Illinois
// variant of the false position, with a bisection whenever it stalls; to |b - a| <= tol.
template <class F>
double crossing(const F& f, double a, double fa, double b, double fb, double tol) {
  int side = 0;
  for (int it = 0; it < 200 && std::abs(b - a) > tol; ++it) {
    double c = (a * fb - b * fa) / (fb - fa);
    if (!(c > std::min(a, b) && c < std::max(a, b)) || it % 8 == 7) c = 0.5 * (a + b);
    const double fc = f(c);
    if (fc == 0) return c;
    if ((fc > 0) == (fb > 0)) {
      b = c;
      fb = fc;
      if (side == -1) fa *= 0.5;
      side = -1;
    } else {
      a = c;
      fa = fc;
      if (side == 1) fb *= 0.5;
      side = 1;
    }
  }
  return 0.5 * (a + b);
}

}  // namespace

Cut measure(const LineProfile& line, double threshold, Across what, double reach, double step) {
  if (!(step > 0) || !(reach > 0)) throw std::invalid_argument("measure: the step and the reach must be positive");
  // g > 0 inside what is measured (printed for a feature, clear for a gap).
  const double sense = what == Across::printed ? 1.0 : -1.0;
  auto g = [&](double t) { return sense * (line.at(t) - threshold); };
  Cut cut;
  const double g0 = g(0);
  if (!(g0 > 0)) {
    cut.outcome = what == Across::printed ? Cut::Outcome::pinch : Cut::Outcome::bridge;
    return cut;
  }
  const double tol = 1e-6;
  double ends[2];
  for (int s = 0; s < 2; ++s) {
    const double dir = s == 0 ? -1.0 : 1.0;
    double t = 0, gt = g0;
    ends[s] = dir * reach;
    bool found = false;
    while (!found && t < reach) {
      const double u = std::min(t + step, reach), gu = g(dir * u);
      if (!(gu > 0)) {
        ends[s] = crossing(g, dir * t, gt, dir * u, gu, tol);
        found = true;
      }
      t = u;
      gt = gu;
    }
    if (!found) cut.outcome = Cut::Outcome::open;
  }
  cut.lo = ends[0];
  cut.hi = ends[1];
  cut.width = cut.hi - cut.lo;
  return cut;
}

}  // namespace linf::litho
