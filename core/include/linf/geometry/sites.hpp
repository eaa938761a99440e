// From layout data to sites.
#pragma once
#include <cstddef>
#include <vector>

#include "linf/geometry/polygons.hpp"
#include "linf/geometry/site.hpp"

namespace linf {

// Merges overlapping and touching polygons (any angle; Boost.Polygon, integer coordinates),
// removes repeated and collinear vertices, and orients rings with the interior on the left.
// Coordinates must lie within +-2^30 so that intersections stay representable. Polygons whose
// boxes overlap or touch are merged together, about `group` of them in one scan (memory); a
// layer of at most `group` polygons is merged in parts on `threads` workers (0: one per core).
// The result depends on neither.
// The result is ordered by each polygon's least vertex. Throws std::invalid_argument on a
// coordinate out of range or flat arrays that do not add up.
PolygonArrays merge_polygons(const FlatPolygons& in, std::size_t group = std::size_t(1) << 16, int threads = 0);
std::vector<Polygon> merge_polygons(const std::vector<Polygon>& in, std::size_t group = std::size_t(1) << 16,
                                    int threads = 0);

// Sites of already merged polygons: every vertex a point site, every edge an open segment site.
Sites sites_of_polygons(const FlatPolygons& merged);
Sites sites_of_polygons(const std::vector<Polygon>& merged);

// Sites of plain input: every segment (and its endpoints) and every point. Segments must not
// cross; they may share endpoints. Each input item is its own shape.
Sites sites_of_plain(const std::vector<Point>& points, const std::vector<Segment>& segments);

}  // namespace linf
