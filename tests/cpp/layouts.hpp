// Drawn and seeded random test layouts, shared by the C++ tests and the benchmark.
#pragma once
#include <cstdint>
#include <random>
#include <vector>

#include "linf/geometry/site.hpp"

namespace linf::testing {

inline Polygon box(Coord x1, Coord y1, Coord x2, Coord y2) { return {{{x1, y1}, {x2, y1}, {x2, y2}, {x1, y2}}, {}}; }

enum class Style { Rectilinear, Octilinear, AnyAngle };

// A handful of shapes in a small field: rectangles (may touch or overlap), a frame with a hole,
// 45-degree or any-angle quadrilaterals, nested shapes. Small enough for brute-force checks.
inline std::vector<Polygon> random_layout(std::uint64_t seed, Style style, int shapes = 6, Coord field = 400) {
  std::mt19937_64 rng(seed);
  auto u = [&](Coord lo, Coord hi) { return std::uniform_int_distribution<Coord>(lo, hi)(rng); };
  std::vector<Polygon> out;
  for (int i = 0; i < shapes; ++i) {
    const Coord x = u(0, field), y = u(0, field), w = u(4, field / 3), h = u(4, field / 3);
    const int pick = int(u(0, 9));
    if (pick <= 4 || style == Style::Rectilinear) {
      if (pick == 0 && w > 12 && h > 12) {  // frame with a hole
        Polygon p = box(x, y, x + w, y + h);
        const Coord t = u(2, std::min(w, h) / 3);
        Ring hole{{x + t, y + t}, {x + w - t, y + t}, {x + w - t, y + h - t}, {x + t, y + h - t}};
        p.holes.push_back(hole);
        out.push_back(p);
      } else if (pick == 1) {  // L shape
        out.push_back({{{x, y}, {x + w, y}, {x + w, y + h / 3 + 2}, {x + w / 3 + 2, y + h / 3 + 2}, {x + w / 3 + 2, y + h}, {x, y + h}}, {}});
      } else {
        out.push_back(box(x, y, x + w, y + h));
      }
    } else if (style == Style::Octilinear) {  // octagon-ish shape with 45-degree cuts
      const Coord c = u(1, std::min(w, h) / 2);
      out.push_back({{{x + c, y}, {x + w - c, y}, {x + w, y + c}, {x + w, y + h - c}, {x + w - c, y + h}, {x + c, y + h}, {x, y + h - c}, {x, y + c}}, {}});
    } else {  // any-angle convex quadrilateral
      out.push_back({{{x, y}, {x + w, y + u(-h / 2, h / 2)}, {x + w + u(-w / 2, w / 2), y + h}, {x + u(-w / 3, w / 3), y + h + u(0, h / 2)}}, {}});
    }
  }
  return out;
}

// A block of many small random layouts side by side (nx by ny fields of 400 DBU): thousands of
// sites, so that the builder's task grid has several levels to group into tiles.
inline std::vector<Polygon> block(std::uint64_t seed, Style style, int nx, int ny) {
  std::vector<Polygon> all;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      for (Polygon p : random_layout(seed * 1000 + std::uint64_t(j * nx + i), style, 8, 300)) {
        for (Point& v : p.outer) v.x += 400 * i, v.y += 400 * j;
        for (Ring& h : p.holes)
          for (Point& v : h) v.x += 400 * i, v.y += 400 * j;
        all.push_back(p);
      }
  return all;
}

}  // namespace linf::testing
