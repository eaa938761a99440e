// A layer's polygons as flat arrays: how the flow holds a layer of millions of shapes (the
// plugin's polygons.Polygons), with no allocation per polygon and nothing copied on the way in.
//
//   FlatPolygons   a view: points x0, y0, x1, y1, ...; rings = point counts, each outer ring
//                  followed by its holes with negative counts;
//   PolygonIndex   where polygon i's rings and points start, and its box (checks the arrays);
//   PolygonArrays  owned flat arrays (Paged: file pages on a full layer), built polygon by
//                  polygon: what merging gives.
#pragma once
#include <cstdint>
#include <vector>

#include "linf/util/box_tree.hpp"
#include "linf/util/paged.hpp"
#include "linf/geometry/site.hpp"

namespace linf {

struct FlatPolygons {
  const std::int64_t* points = nullptr;
  std::size_t n_points = 0;  // points, not coordinates
  const std::int64_t* rings = nullptr;
  std::size_t n_rings = 0;
};

class PolygonIndex {
 public:
  // Throws std::invalid_argument if the rings do not add up to the points, a hole comes first,
  // or a coordinate lies outside +-2^30 (intersections must stay representable; boxes are 32-bit).
  explicit PolygonIndex(const FlatPolygons& in);
  std::size_t size() const { return first_ring_.size() - 1; }
  std::size_t points(std::size_t i) const { return first_point_[i + 1] - first_point_[i]; }
  Polygon polygon(std::size_t i) const;
  // Its outer ring's box; {0, 0, 0, 0} for a polygon of no points.
  const IntBox& box(std::size_t i) const { return boxes_[i]; }
  // Calls f(first point, count, is_outer) for each ring of polygon i.
  template <class F>
  void rings(std::size_t i, F&& f) const {
    std::size_t at = first_point_[i];
    for (std::size_t k = first_ring_[i]; k < first_ring_[i + 1]; ++k) {
      const std::int64_t c = in_.rings[k];
      const std::size_t n = std::size_t(c < 0 ? -c : c);
      f(in_.points + 2 * at, n, k == first_ring_[i]);
      at += n;
    }
  }

 private:
  FlatPolygons in_;
  Paged<std::size_t> first_ring_, first_point_;  // per polygon, plus one past the end
  Paged<IntBox> boxes_;
};

struct PolygonArrays {
  Paged<std::int64_t> points, rings;
  std::size_t count = 0;
  void add(const Polygon& p);
  FlatPolygons view() const { return {points.data(), points.size() / 2, rings.data(), rings.size()}; }
};

PolygonArrays flat_of(const std::vector<Polygon>& polygons);
std::vector<Polygon> polygons_of(const FlatPolygons& in);

}  // namespace linf
