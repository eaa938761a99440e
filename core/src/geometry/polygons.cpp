#include "linf/geometry/polygons.hpp"

#include <algorithm>
#include <stdexcept>

namespace linf {

PolygonIndex::PolygonIndex(const FlatPolygons& in) : in_(in) {
  std::size_t at = 0;
  for (std::size_t k = 0; k < in.n_rings; ++k) {
    const std::int64_t c = in.rings[k];
    const std::size_t n = std::size_t(c < 0 ? -c : c);
    if (n > in.n_points - at) throw std::invalid_argument("rings count more points than there are");
    if (c < 0 && first_ring_.empty()) throw std::invalid_argument("a hole (negative count) must follow its outer ring");
    std::int64_t x1 = kCoordLimit, y1 = kCoordLimit, x2 = -kCoordLimit, y2 = -kCoordLimit;
    for (std::size_t i = at; i < at + n; ++i) {
      const std::int64_t x = in.points[2 * i], y = in.points[2 * i + 1];
      check_range(x, y);
      x1 = std::min(x1, x), y1 = std::min(y1, y), x2 = std::max(x2, x), y2 = std::max(y2, y);
    }
    if (c >= 0) {
      first_ring_.push_back(k), first_point_.push_back(at);
      boxes_.push_back(n ? IntBox{std::int32_t(x1), std::int32_t(y1), std::int32_t(x2), std::int32_t(y2)} : IntBox{0, 0, 0, 0});
    }
    at += n;
  }
  if (at != in.n_points) throw std::invalid_argument("points left over after the last ring");
  first_ring_.push_back(in.n_rings), first_point_.push_back(at);
}

Polygon PolygonIndex::polygon(std::size_t i) const {
  Polygon p;
  rings(i, [&](const std::int64_t* xy, std::size_t n, bool outer) {
    Ring r(n);
    for (std::size_t j = 0; j < n; ++j) r[j] = {xy[2 * j], xy[2 * j + 1]};
    if (outer) p.outer = std::move(r);
    else p.holes.push_back(std::move(r));
  });
  return p;
}

void PolygonArrays::add(const Polygon& p) {
  auto ring = [&](const Ring& r, std::int64_t sign) {
    for (const Point& q : r) points.push_back(q.x), points.push_back(q.y);
    rings.push_back(sign * std::int64_t(r.size()));
  };
  ring(p.outer, 1);
  for (const Ring& h : p.holes) ring(h, -1);
  ++count;
}

PolygonArrays flat_of(const std::vector<Polygon>& polygons) {
  PolygonArrays out;
  for (const Polygon& p : polygons) out.add(p);
  return out;
}

std::vector<Polygon> polygons_of(const FlatPolygons& in) {
  const PolygonIndex ix(in);
  std::vector<Polygon> out;
  out.reserve(ix.size());
  for (std::size_t i = 0; i < ix.size(); ++i) out.push_back(ix.polygon(i));
  return out;
}

}  // namespace linf
