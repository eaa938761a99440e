#include "linf/io/picture_grid.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace linf {

PictureGrid picture_grid(const FlatPolygons& layer, int cells_across, double large) {
  if (cells_across <= 0) throw std::invalid_argument("coverage: no cells");
  const PolygonIndex ix(layer);
  PictureGrid c;
  std::int64_t x1 = INT32_MAX, y1 = INT32_MAX, x2 = INT32_MIN, y2 = INT32_MIN;
  for (std::size_t i = 0; i < ix.size(); ++i) {
    if (ix.points(i) == 0) continue;
    const IntBox& b = ix.box(i);
    x1 = std::min<std::int64_t>(x1, b.x1), y1 = std::min<std::int64_t>(y1, b.y1);
    x2 = std::max<std::int64_t>(x2, b.x2), y2 = std::max<std::int64_t>(y2, b.y2);
  }
  if (x1 > x2) return c;  // no shapes
  c.x0 = double(x1), c.y0 = double(y1);
  c.cell = std::max(1.0, double(std::max(x2 - x1, y2 - y1)) / cells_across);
  c.nx = std::max(1, int(std::ceil(double(x2 - x1) / c.cell)));
  c.ny = std::max(1, int(std::ceil(double(y2 - y1) / c.cell)));
  c.cells.assign(std::size_t(c.nx) * std::size_t(c.ny), 0);
  auto at = [&](double v, double lo, int n) { return std::clamp(int(std::floor((v - lo) / c.cell)), 0, n - 1); };
  for (std::size_t i = 0; i < ix.size(); ++i) {
    if (ix.points(i) == 0) continue;
    const IntBox& b = ix.box(i);
    if (double(b.x2) - double(b.x1) >= large * c.cell && double(b.y2) - double(b.y1) >= large * c.cell) {
      c.large.add(ix.polygon(i));
      continue;
    }
    const int i1 = at(b.x1, c.x0, c.nx), i2 = at(b.x2, c.x0, c.nx), j1 = at(b.y1, c.y0, c.ny), j2 = at(b.y2, c.y0, c.ny);
    for (int j = j1; j <= j2; ++j) std::fill_n(c.cells.begin() + std::ptrdiff_t(j) * c.nx + i1, i2 - i1 + 1, 1);
  }
  return c;
}

}  // namespace linf
