// A layer's rings checked, and a ring clipped to a window: what the windows the lithography
// model images need of the layer (printability.cpp, opc.cpp). Internal to linf_litho.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#include "linf/geometry/polygons.hpp"
#include "linf/geometry/site.hpp"

namespace linf::litho {

// Throws std::invalid_argument("<who>: ...") unless the rings add up to the points, none is
// empty and the first is an outer ring.
void check_rings(const FlatPolygons& layer, const std::string& who);

// The ring of n points `pts` (x, y pairs in DBU) clipped to the box [lx, hx] x [ly, hy] given in
// half DBU, the result in half DBU: a crossing of a side at an angle is rounded to the nearest
// half DBU; consecutive repeated points are dropped. Fewer than 3 points: nothing is left.
Ring clip_ring(const std::int64_t* pts, std::size_t n, std::int64_t lx, std::int64_t ly, std::int64_t hx,
               std::int64_t hy);

}  // namespace linf::litho
