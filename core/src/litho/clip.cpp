#include "litho/clip.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

namespace linf::litho {

void check_rings(const FlatPolygons& layer, const std::string& who) {
  auto fail = [&](const char* what) { throw std::invalid_argument(who + ": " + what); };
  std::size_t at = 0;
  for (std::size_t k = 0; k < layer.n_rings; ++k) {
    const std::int64_t c = layer.rings[k];
    if (c == 0) fail("a ring of no points in the layer");
    if (c < 0 && k == 0) fail("the layer's first ring is a hole");
    at += std::size_t(c < 0 ? -c : c);
    if (at > layer.n_points) fail("the layer's rings hold more points than its points array");
  }
  if (at != layer.n_points) fail("the layer's rings do not add up to its points");
}

// Sutherland-Hodgman against the box, one side at a time. On a concave ring it can leave
// zero-width runs along a side; the mask's spectrum integrates edge by edge (Green's theorem),
// where such runs cancel, so the clipped region's coefficients are exact (but for the rounding
// of a slanted edge's crossing to the DBU grid).
Ring clip_ring(const std::int64_t* pts, std::size_t n, std::int64_t lx, std::int64_t ly, std::int64_t hx,
               std::int64_t hy) {
  std::vector<std::pair<double, double>> a, b;
  a.reserve(n + 8);
  for (std::size_t j = 0; j < n; ++j) a.push_back({2.0 * double(pts[2 * j]), 2.0 * double(pts[2 * j + 1])});
  for (int side = 0; side < 4 && !a.empty(); ++side) {
    // inside: value(p) >= 0
    auto value = [&](const std::pair<double, double>& p) {
      switch (side) {
        case 0: return p.first - double(lx);
        case 1: return double(hx) - p.first;
        case 2: return p.second - double(ly);
        default: return double(hy) - p.second;
      }
    };
    b.clear();
    for (std::size_t j = 0; j < a.size(); ++j) {
      const auto& p = a[j];
      const auto& q = a[(j + 1) % a.size()];
      const double vp = value(p), vq = value(q);
      if (vp >= 0) b.push_back(p);
      if ((vp >= 0) != (vq >= 0) && vp != 0 && vq != 0) {
        const double t = vp / (vp - vq);
        std::pair<double, double> s{p.first + t * (q.first - p.first), p.second + t * (q.second - p.second)};
        // Exactly on the side it crosses; the other coordinate to the half-DBU grid.
        if (side < 2) s.first = side == 0 ? double(lx) : double(hx), s.second = std::round(s.second);
        else s.second = side == 2 ? double(ly) : double(hy), s.first = std::round(s.first);
        b.push_back(s);
      }
    }
    std::swap(a, b);
  }
  Ring ring;
  ring.reserve(a.size());
  for (const auto& p : a) {
    const Point q{Coord(std::llround(p.first)), Coord(std::llround(p.second))};
    if (ring.empty() || ring.back() != q) ring.push_back(q);
  }
  while (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();
  return ring;
}

}  // namespace linf::litho
