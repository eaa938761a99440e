// Context ids: what a gauge sees of its layer, as one 64-bit number, so that gauges of one
// type in one and the same neighbourhood can stand for each other (docs/design.md, "Gauge
// contexts").
//
// The context of a point c is the layer clipped to the square [c - r, c + r]^2, exactly, with c
// at the origin, taken up to the eight symmetries of the square (rotations by 90 degrees and
// mirrors). Two points have the same id if and only if (but for a 64-bit hash collision) one
// neighbourhood is the other moved and turned or mirrored.
#pragma once
#include <cstdint>
#include <vector>

#include "linf/geometry/polygons.hpp"

namespace linf {

// The id of the empty neighbourhood at `radius` (no geometry within the square).
std::uint64_t empty_context_id(std::int64_t radius);

// One id per point of `at` (x0, y0, x1, y1, ... in DBU; rounded to the nearest half DBU, as
// gauge centres are midpoints of integer points), of the merged `layer` within `radius` DBU in
// the L-infinity sense. `threads`: 0 for one per core. Throws std::invalid_argument if the
// radius is not in [1, 2^26) or a point lies outside +-2^30.
std::vector<std::uint64_t> context_ids(const FlatPolygons& layer, const std::vector<double>& at, std::int64_t radius,
                                       int threads = 0);

// The same with the layer already indexed (its boxes in a BoxTree over the index's polygons).
std::vector<std::uint64_t> context_ids(const PolygonIndex& layer, const BoxTree& boxes, const double* at,
                                       std::size_t n_points, std::int64_t radius, int threads = 0);

}  // namespace linf
