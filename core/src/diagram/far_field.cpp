#include "far_field.hpp"

#include <algorithm>
#include <cmath>

namespace linf::detail {

namespace {

// A stretch of one side of the inner box between two border points, [lo, hi] along the side,
// and a bound of the L-inf distance to the nearest site over it.
struct Stretch {
  double lo, hi, f;
};

}  // namespace

std::vector<int> far_field_sites(const SiteList& sites, const Point& origin, const Box& inner,
                                 const std::vector<BorderMark>& marks) {
  std::vector<int> ids;
  if (marks.empty()) {
    for (std::size_t i = 0; i < sites.size(); ++i) ids.push_back(int(i));
    return ids;
  }
  const double tol = 1e-9 * std::max({1.0, std::fabs(inner.x1), std::fabs(inner.x2), std::fabs(inner.y1),
                                      std::fabs(inner.y2)});
  // Sides: x = x1, x = x2 (positions along y), y = y1, y = y2 (along x).
  const double line[4] = {inner.x1, inner.x2, inner.y1, inner.y2};
  const double lo_end[4] = {inner.y1, inner.y1, inner.x1, inner.x1}, hi_end[4] = {inner.y2, inner.y2, inner.x2, inner.x2};
  auto corner_bound = [&](double x, double y) {  // f is 1-Lipschitz: bounded from every mark
    double f = INFINITY;
    for (const BorderMark& m : marks) f = std::min(f, m.d + std::max(std::fabs(m.v.x - x), std::fabs(m.v.y - y)));
    return f;
  };
  std::vector<Stretch> stretches[4];
  double reach[4];  // the largest bound on each side
  for (int s = 0; s < 4; ++s) {
    const bool vertical = s < 2;
    std::vector<std::pair<double, double>> at;  // (position, distance)
    for (const BorderMark& m : marks)
      if (std::fabs((vertical ? m.v.x : m.v.y) - line[s]) <= tol) at.push_back({vertical ? m.v.y : m.v.x, m.d});
    const double c0x = vertical ? line[s] : lo_end[s], c0y = vertical ? lo_end[s] : line[s];
    const double c1x = vertical ? line[s] : hi_end[s], c1y = vertical ? hi_end[s] : line[s];
    at.push_back({lo_end[s], corner_bound(c0x, c0y)});
    at.push_back({hi_end[s], corner_bound(c1x, c1y)});
    std::sort(at.begin(), at.end());
    reach[s] = 0;
    for (std::size_t k = 0; k + 1 < at.size(); ++k) {
      const double f = std::max(at[k].second, at[k + 1].second) + tol;
      stretches[s].push_back({at[k].first - tol, at[k + 1].first + tol, f});
      reach[s] = std::max(reach[s], f);
    }
  }
  const double ox = double(origin.x), oy = double(origin.y);
  for (std::size_t i = 0; i < sites.size(); ++i) {
    const Site& t = sites[i];
    const double x1 = double(std::min(t.a.x, t.b.x)) - ox, x2 = double(std::max(t.a.x, t.b.x)) - ox;
    const double y1 = double(std::min(t.a.y, t.b.y)) - oy, y2 = double(std::max(t.a.y, t.b.y)) - oy;
    bool keep = false;
    for (int s = 0; s < 4 && !keep; ++s) {
      const bool vertical = s < 2;
      const double gap = s == 0 ? x1 - line[0] : s == 1 ? line[1] - x2 : s == 2 ? y1 - line[2] : line[3] - y2;
      if (gap > reach[s]) continue;
      const double a = vertical ? y1 : x1, b = vertical ? y2 : x2;  // the site's extent along the side
      const auto& st = stretches[s];
      // Stretches are consecutive: those that can reach [a, b] start at the last one ending
      // before a - reach.
      auto it = std::lower_bound(st.begin(), st.end(), a - reach[s], [](const Stretch& x, double v) { return x.hi < v; });
      for (; it != st.end() && it->lo <= b + reach[s]; ++it)
        if (gap <= it->f && it->lo - it->f <= b && a <= it->hi + it->f) {
          keep = true;
          break;
        }
    }
    if (keep) ids.push_back(int(i));
  }
  return ids;
}

}  // namespace linf::detail
